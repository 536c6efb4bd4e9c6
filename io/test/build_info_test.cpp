// Tests of what a binary says it was built from.
#include "io/build_info.hpp"

#include <doctest/doctest.h>

#include <cctype>
#include <string>

namespace nsb {

TEST_CASE("build_info names a version, a revision, a build type and a compiler") {
  const io::BuildInfo& b = io::build_info();
  CHECK(b.version.find('.') != std::string::npos);
  CHECK(!b.build_type.empty());
  CHECK(!b.compiler.empty());
  // "unknown" outside git; else 12 hex digits, "-dirty" when the tree had changes.
  if (b.revision != "unknown") {
    REQUIRE(b.revision.size() >= 12);
    for (std::size_t i = 0; i < 12; ++i) CHECK(std::isxdigit(b.revision[i]) != 0);
    CHECK((b.revision.size() == 12 || b.revision.substr(12) == "-dirty"));
  }
  CHECK(&io::build_info() == &b);  // computed once
}

}  // namespace nsb
