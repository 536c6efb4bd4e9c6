// Number formatting shared by the commands: the shortest text that reads back to the same
// double (std::to_chars), with no exception path for any value, subnormal numbers included.
#pragma once

#include <string>

namespace nsb::app {

// Shortest round-trip text of a finite x; "nan", "inf" or "-inf" otherwise (text output only).
std::string shortest(double x);
// The same for JSON, which has no NaN or infinity: a non-finite x is written null.
std::string json_number(double x);
// A JSON string literal of text (quotes, backslashes and control characters escaped).
std::string json_string(const std::string& text);

}  // namespace nsb::app
