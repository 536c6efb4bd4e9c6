// The distance between two spellings, for the "did you mean" hints of unknown names (scene
// keys, output groups).
#pragma once

#include <cstddef>
#include <string_view>

namespace nsb::io {

// The Levenshtein distance of a and b: the fewest insertions, deletions and substitutions of
// one byte that turn a into b.
std::size_t edit_distance(std::string_view a, std::string_view b);

}  // namespace nsb::io
