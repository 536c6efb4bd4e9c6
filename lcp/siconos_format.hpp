// Reader and writer for LCPs in Siconos Numerics' text format (the files of data/siconos-lcp).
//
// Dense storage, as written by Siconos 4.4:
//   line 1..: n, the storage type (0 = dense), then the matrix sizes n n, and n n again
//             (six integers, on one or more lines);
//   next n lines: M, one COLUMN per line (n numbers each): line j holds M(0..n-1, j);
//   next line: q (n numbers);
//   anything after q is a comment.
// Blank lines between these parts are skipped. Storage type 1 (sparse block, the *_block.dat
// files) is rejected with a message naming it: the same problems are in the dense files.
#pragma once

#include "lcp/lcp.hpp"

#include <cstdint>
#include <filesystem>
#include <istream>
#include <ostream>
#include <stdexcept>
#include <string>

namespace nsb::lcp {

// A malformed file: what() is "<file>:<line>: <what was found>; expected <what is allowed>"
// ("<file>: ..." with line = 0 when the file cannot be opened).
struct FormatError : std::invalid_argument {
  FormatError(const std::string& file, int line, const std::string& what);
  std::string file;
  int line = 0;
};

// Throws FormatError for a malformed file (also: size mismatch, NaN or Inf, an empty file, an
// n larger than the file can hold), and FormatError with line 0 if the file cannot be opened
// or is not a regular file (a FIFO or a device is refused, never read). Reads no further than
// q, and allocates nothing before the header's n is known to fit in the file.
Problem read_siconos_lcp(const std::filesystem::path& file);
// The same from a stream; `name` is used in messages, `size` is the stream's length in bytes
// when known (it bounds n before M is allocated).
Problem parse_siconos_lcp(std::istream& in, const std::string& name,
                          std::uintmax_t size = UINTMAX_MAX);

// Writes p in the dense format above (header "n", "0", "n", "n", "n n" as Siconos writes it),
// every number with 17 significant digits, so that read_siconos_lcp returns p bit for bit.
// `comment` (may be empty) follows q, one "# "-prefixed line per line of it: the reader
// stops after q and never reads it. Throws std::invalid_argument for a non-finite entry or a
// non-square M (the reader could not read the file back).
void write_siconos_lcp(std::ostream& out, const Problem& p, const std::string& comment = {});

}  // namespace nsb::lcp
