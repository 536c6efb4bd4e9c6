// Tests of what a binary says it was built from.
#include "io/build_info.hpp"

#include <doctest/doctest.h>

#include <cctype>
#include <string>

namespace nsb {

TEST_CASE("build_info names a version, a revision, a build type, a compiler and the libraries") {
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
  REQUIRE(b.libraries.size() == 4);
  const char* names[] = {"Eigen", "Boost", "GSL", "toml++"};
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(b.libraries[i].first == names[i]);
    CHECK(std::isdigit(static_cast<unsigned char>(b.libraries[i].second.front())) != 0);
  }
  CHECK(&io::build_info() == &b);  // computed once
}

}  // namespace nsb
