// nsbridge --version: what a bug report needs to reproduce a result.
#include "app/commands.hpp"

#include "nsb_git_revision.hpp"

#include <CLI/Version.hpp>
#include <Eigen/Core>
#include <boost/version.hpp>
#include <gsl/gsl_version.h>
#include <toml++/toml.h>

#include <string>

namespace nsb::app {

namespace {

std::string compiler() {
#if defined(__clang__)
  return "clang " __clang_version__;
#elif defined(__GNUC__)
  return "gcc " __VERSION__;
#else
  return "unknown compiler";
#endif
}

std::string dotted(int major, int minor, int patch) {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

}  // namespace

std::string version_text() {
  return std::string("nsbridge ") + NSB_VERSION + "\n" +
         "revision   " + NSB_GIT_REVISION + " (git, at build time)\n" +
         "build      " + (std::string(NSB_BUILD_TYPE).empty() ? "none" : NSB_BUILD_TYPE) + "\n" +
         "compiler   " + compiler() + "\n" +
         "Eigen      " + dotted(EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION) +
         "\n" +
         "Boost      " + dotted(BOOST_VERSION / 100000, BOOST_VERSION / 100 % 1000,
                                BOOST_VERSION % 100) + "\n" +
         "GSL        " + GSL_VERSION + "\n" +
         "toml++     " + dotted(TOML_LIB_MAJOR, TOML_LIB_MINOR, TOML_LIB_PATCH) + "\n" +
         "CLI11      " + CLI11_VERSION;
}

}  // namespace nsb::app
