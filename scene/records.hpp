// Ground-motion record files (docs/ground-motions.md): the PEER NGA .AT2 format, two columns
// "t a" per line and CSV with a header naming the columns t and a. Each reader returns a
// models::Record (m/s^2) checked as models::validate_record checks a record built in code.
//
// Errors throw std::invalid_argument "<file>:<line>: <what>" (missing file, non-numeric
// token, NPTS mismatch, non-increasing time, NaN or infinite value).
#pragma once

#include "models/ground_motion.hpp"

#include <filesystem>
#include <istream>
#include <string>

namespace nsb::scene {

models::Record read_at2(const std::filesystem::path&, double g = 9.81);          // PEER NGA .AT2 (units of g)
models::Record read_two_column(const std::filesystem::path&, double unit = 1.0); // "t a" per line; a*unit -> m/s^2
models::Record read_csv(const std::filesystem::path&, double unit = 1.0);        // header line, columns t,a
// The same from a stream; `name` stands for the file in messages. The path readers refuse
// anything but a regular file (a FIFO or a device could block or never end).
models::Record read_at2(std::istream& in, const std::string& name, double g = 9.81);
models::Record read_two_column(std::istream& in, const std::string& name, double unit = 1.0);
models::Record read_csv(std::istream& in, const std::string& name, double unit = 1.0);

}  // namespace nsb::scene
