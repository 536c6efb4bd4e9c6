// JSON text in one form for every file nsbridge writes (summary.json, the sweep's and the
// figures' JSON, `nsbridge lcp --json`): numbers in their shortest round-trip form, strings
// with every control character escaped (RFC 8259, section 7).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace nsb::io {

// The shortest text that reads back to the same double (std::to_chars); JSON has no NaN or
// infinity, so a non-finite v is written null.
std::string json_number(double v);
void append_json_number(std::string& out, double v);

// An integer as JSON text.
void append_integer(std::string& out, std::int64_t v);

// A JSON string literal of text: '"' and '\' escaped, '\n', '\r', '\t' by name, every other
// control character (< 0x20) as \u00XX. Bytes >= 0x80 (UTF-8) are copied as they are.
std::string json_string(std::string_view text);

}  // namespace nsb::io
