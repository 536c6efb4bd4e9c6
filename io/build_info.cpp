#include "io/build_info.hpp"

#include "nsb_git_revision.hpp"

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

}  // namespace

const BuildInfo& build_info() {
  static const BuildInfo info{NSB_VERSION, NSB_GIT_REVISION,
                              std::string(NSB_BUILD_TYPE).empty() ? "none" : NSB_BUILD_TYPE,
                              compiler()};
  return info;
}

}  // namespace nsb::io
