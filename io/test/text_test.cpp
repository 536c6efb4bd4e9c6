// Tests of the JSON and CSV text every output file is written in: the number form (shortest
// round trip, non-finite as null or empty), string escaping (RFC 8259, section 7) and CSV
// fields (RFC 4180).
#include "io/csv.hpp"
#include "io/json.hpp"

#include <doctest/doctest.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <string>

namespace nsb::io {
namespace {

// The double a text reads back to (std::from_chars, which reads subnormal numbers too).
double read_back(const std::string& s) {
  double v = 0.0;
  std::from_chars(s.data(), s.data() + s.size(), v);
  return v;
}

}  // namespace

TEST_CASE("numbers: the shortest text that reads back to the same double") {
  CHECK(csv_number(0.1) == "0.1");
  CHECK(csv_number(1e-5) == "1e-05");
  CHECK(csv_number(0.1 + 0.2) == "0.30000000000000004");
  CHECK(csv_number(-2.0) == "-2");
  CHECK(csv_number(1.0 / 3.0) == "0.3333333333333333");
  for (const double v : {1.0 / 3.0, 1e-300, 4.9e-324, 1.7976931348623157e308, -0.0}) {
    CHECK(read_back(csv_number(v)) == v);
    CHECK(json_number(v) == csv_number(v));
  }
}

TEST_CASE("a non-finite number: empty in CSV, null in JSON, spelled out for people") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(csv_number(nan).empty());
  CHECK(csv_number(-inf).empty());
  CHECK(json_number(nan) == "null");
  CHECK(json_number(inf) == "null");
  CHECK(shortest(nan) == "nan");
  CHECK(shortest(-inf) == "-inf");
  CHECK(shortest(0.25) == "0.25");
}

TEST_CASE("three_digits: numbers in messages print as %.3g, not std::to_string's six decimals") {
  CHECK(nsb::io::three_digits(1e-9) == "1e-09");  // std::to_string gives "0.000000"
  CHECK(nsb::io::three_digits(0.0123456) == "0.0123");
  CHECK(nsb::io::three_digits(4567.0) == "4.57e+03");
  CHECK(nsb::io::three_digits(0.501) == "0.501");
}

TEST_CASE("integers") {
  std::string s;
  append_integer(s, -9223372036854775807LL);
  CHECK(s == "-9223372036854775807");
}

TEST_CASE("JSON strings: quotes, backslashes and every control character are escaped") {
  CHECK(json_string("plain") == "\"plain\"");
  CHECK(json_string("a\"b\\c") == "\"a\\\"b\\\\c\"");
  CHECK(json_string("l1\nl2\r\t") == "\"l1\\nl2\\r\\t\"");
  CHECK(json_string(std::string("\x01\x1f", 2)) == "\"\\u0001\\u001f\"");
  CHECK(json_string(std::string("nul\0x", 5)) == "\"nul\\u0000x\"");
  // UTF-8 passes through: JSON text is UTF-8 (RFC 8259, section 8.1).
  CHECK(json_string("Coulomb \xce\xbc") == "\"Coulomb \xce\xbc\"");
}

TEST_CASE("CSV fields: quoted only when they must be, and read back") {
  CHECK(csv_quote("plain") == "plain");
  CHECK(csv_quote("a,b") == "\"a,b\"");
  CHECK(csv_quote("say \"hi\"") == "\"say \"\"hi\"\"\"");
  CHECK(csv_quote("two\nlines") == "\"two\nlines\"");
  const std::string line = "1, x ," + csv_quote("a,\"b\"") + ",,\r";
  const auto f = csv_fields(line);
  REQUIRE(f.size() == 5);
  CHECK(f[0] == "1");
  CHECK(f[1] == "x");  // unquoted fields are trimmed
  CHECK(f[2] == "a,\"b\"");
  CHECK(f[3].empty());
  CHECK(f[4].empty());
}

}  // namespace nsb::io
