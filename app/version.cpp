// nsbridge --version: what a bug report needs to reproduce a result.
#include "app/commands.hpp"

#include "io/build_info.hpp"

#include <CLI/Version.hpp>
#include <Eigen/Core>
#include <boost/version.hpp>
#include <gsl/gsl_version.h>
#include <toml++/toml.h>

#include <string>

namespace nsb::app {

namespace {

std::string dotted(int major, int minor, int patch) {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

}  // namespace

std::string version_text() {
  const io::BuildInfo& b = io::build_info();
  return "nsbridge " + b.version + "\n" +
         "revision   " + b.revision + " (git, at build time)\n" +
         "build      " + b.build_type + "\n" +
         "compiler   " + b.compiler + "\n" +
         "Eigen      " + dotted(EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION) +
         "\n" +
         "Boost      " + dotted(BOOST_VERSION / 100000, BOOST_VERSION / 100 % 1000,
                                BOOST_VERSION % 100) + "\n" +
         "GSL        " + GSL_VERSION + "\n" +
         "toml++     " + dotted(TOML_LIB_MAJOR, TOML_LIB_MINOR, TOML_LIB_PATCH) + "\n" +
         "CLI11      " + CLI11_VERSION;
}

}  // namespace nsb::app
