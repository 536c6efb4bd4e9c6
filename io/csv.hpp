// CSV text in one form for every table nsbridge writes (history.csv, events.csv, the sweep's
// results.csv, the figures' tables): RFC 4180 fields, numbers in their shortest round-trip
// form, a non-finite number as an empty field (which gnuplot and pandas read as missing).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace nsb::io {

// The shortest text that reads back to the same double (std::to_chars): 0.1, 1e-05,
// 0.30000000000000004. Empty for NaN and infinities: "nan" never appears in a CSV file.
std::string csv_number(double v);
void append_csv_number(std::string& out, double v);

// The shortest round-trip text of a finite x, and "nan", "inf" or "-inf" otherwise: for text
// read by people (the terminal).
std::string shortest(double x);

// x with three significant digits, as printf's %.3g writes it (1e-09, 0.0123, 4.57e+03): for
// a number in a message or warning, where the reader wants its size, not every digit. Files
// never use it; they hold csv_number's round-trip text.
std::string three_digits(double x);

// s as a CSV field: quoted (RFC 4180) when it holds a comma, a quote or a line break.
std::string csv_quote(std::string_view s);

// The fields of one CSV line; quoted fields may hold commas and doubled quotes. Unquoted
// fields are trimmed of spaces and tabs; a '\r' outside quotes is dropped.
std::vector<std::string> csv_fields(const std::string& line);

}  // namespace nsb::io
