// Ground-motion record files (docs/ground-motions.md): the PEER .AT2 format (the NGA header
// "NPTS= n, DT= dt SEC" and the older "n dt NPTS, DT"), whitespace-separated text ("t a" per
// line, or acceleration values only with the step given by the caller) and CSV (a header that
// names the columns and their units, or none). Each reader returns a models::Record (m/s^2, or
// rad/s^2 for an angular record) checked as models::validate_record checks a record built in
// code.
//
// Errors throw std::invalid_argument "<file>:<line>: <what>" (missing file, non-numeric
// token, NPTS mismatch, non-increasing time, NaN or infinite value, an unknown unit or one
// that disagrees with the caller's). A fragment of the file quoted in a message has its
// non-printable bytes escaped (\x00) and is cut to a readable length.
#pragma once

#include "models/ground_motion.hpp"

#include <filesystem>
#include <istream>
#include <string>

namespace nsb::scene {

// What the caller (a scene) says of a record beyond its file.
struct RecordKeys {
  double unit = 1.0;      // [m/s^2 per file value] ([rad/s^2] for an angular record), > 0
  std::string unit_key;   // the key that set unit, "" when unit is the default 1: a unit the
                          //   file names then sets the values' unit; otherwise it must agree
  double dt = 0.0;        // [s] step of a file of acceleration values only; 0: not given
  std::string dt_key = "dt";  // the key that gives dt, named when a file needs it
  bool angular = false;   // angular accelerations (rad/s^2): a header may only say [rad/s^2]
};

// Two units agree when they differ by less than this fraction: the g values in use (9.80665,
// the standard, and 9.81) differ by 3.4e-4; distinct units differ by a factor of 2.5 or more.
inline constexpr double kUnitAgreement = 1e-3;

// Factor to m/s^2 of an acceleration unit written in a header ("g", "m/s^2", "gal", ...;
// case, spaces and "²" for "^2" do not matter); 0 when the unit is unknown.
double acceleration_unit(std::string_view unit);

models::Record read_at2(const std::filesystem::path&, double g = 9.81);          // PEER .AT2 (units of g)
models::Record read_two_column(const std::filesystem::path&, double unit = 1.0); // "t a" per line; a*unit -> m/s^2
models::Record read_csv(const std::filesystem::path&, double unit = 1.0);        // columns t,a (header optional)
// With the caller's keys: the unit it gives must agree with a unit the file names, and dt
// makes a text file one of acceleration values only (any number per line, t_i = i dt).
models::Record read_at2(const std::filesystem::path&, double g, const RecordKeys&);
models::Record read_two_column(const std::filesystem::path&, const RecordKeys&);
models::Record read_csv(const std::filesystem::path&, const RecordKeys&);
// The same from a stream; `name` stands for the file in messages. The path readers refuse
// anything but a regular file (a FIFO or a device could block or never end).
models::Record read_at2(std::istream& in, const std::string& name, double g = 9.81);
models::Record read_two_column(std::istream& in, const std::string& name, double unit = 1.0);
models::Record read_csv(std::istream& in, const std::string& name, double unit = 1.0);
models::Record read_at2(std::istream& in, const std::string& name, double g, const RecordKeys&);
models::Record read_two_column(std::istream& in, const std::string& name, const RecordKeys&);
models::Record read_csv(std::istream& in, const std::string& name, const RecordKeys&);

}  // namespace nsb::scene
