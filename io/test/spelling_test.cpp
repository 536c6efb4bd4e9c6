// Tests of the edit distance behind the "did you mean" hints: distances counted by hand.
#include "io/spelling.hpp"

#include <doctest/doctest.h>

namespace nsb::io {

TEST_CASE("edit distance: hand-counted edits") {
  CHECK(edit_distance("", "") == 0);
  CHECK(edit_distance("", "abc") == 3);        // three insertions
  CHECK(edit_distance("abc", "") == 3);        // three deletions
  CHECK(edit_distance("step", "step") == 0);
  CHECK(edit_distance("stpe", "step") == 2);   // a transposition is two substitutions
  CHECK(edit_distance("kitten", "sitting") == 3);  // k->s, e->i, insert g
  CHECK(edit_distance("energi", "energy") == 1);
  CHECK(edit_distance("bent", "bents") == 1);
  // Symmetric: every edit has its inverse.
  CHECK(edit_distance("sitting", "kitten") == 3);
}

}  // namespace nsb::io
