#include "io/build_info.hpp"

#include "nsb_git_revision.hpp"

#include <Eigen/Core>
#include <boost/version.hpp>
#include <gsl/gsl_version.h>
#include <toml++/toml.h>

namespace nsb::io {

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

const BuildInfo& build_info() {
  static const BuildInfo info{
      NSB_VERSION,
      NSB_GIT_REVISION,
      std::string(NSB_BUILD_TYPE).empty() ? "none" : NSB_BUILD_TYPE,
      compiler(),
      {{"Eigen", dotted(EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION)},
       {"Boost", dotted(BOOST_VERSION / 100000, BOOST_VERSION / 100 % 1000, BOOST_VERSION % 100)},
       {"GSL", GSL_VERSION},
       {"toml++", dotted(TOML_LIB_MAJOR, TOML_LIB_MINOR, TOML_LIB_PATCH)}}};
  return info;
}

}  // namespace nsb::io
