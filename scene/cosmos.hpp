// COSMOS strong-motion data files, processed (V1, V2; CESMD's `.V2c`), in the fixed-field
// format of the COSMOS Strong Motion Data Format, version 1.20 (COSMOS Strong Motion Programs
// Board, 15 August 2001; docs/ground-motions.md, "COSMOS V2"). Each channel of a file is
//   - a text header: line 1 names the data type and says "(Format v01.20 with N text
//     lines)"; line 5 holds the network and station codes (columns 26-34) and the station
//     name (from column 41);
//   - an integer header: a line "<n> Integer-header values follow on <m> lines, Format=
//     (10I8)", then the values in that Fortran format; -999 stands for "unknown";
//   - a real header, the same with "Real-header values" (e.g. Format= (6F13.6));
//   - "<k> Comment line(s) follow ...", then k lines;
//   - the acceleration block: "<npts> acceleration pts, approx <T> secs, units=cm/sec2 (04),
//     Format=(8F10.5)", then npts values in that format;
//   - optionally velocity and displacement blocks and an end-of-data line, skipped here.
// The parameters read (numbered from 1 as the specification numbers them): integer 1, the
// processing stage (1 or 2: a record in physical units); integer 2, the kind of series (1:
// acceleration); integer 3, the physical unit (Table 2: 2 g, 4 cm/s^2, 7 in/s^2, 10 gal, 11
// milli-g); integers 40, 42-45, the record's start (year, month, day, hour, minute); integer
// 54, the sensor's azimuth (0-360 degrees, 500/501 radial/transverse, 600/601 longitudinal/
// tangential, 700/701 H1/H2: horizontal; 400-402: vertical); real 62, the sampling interval
// in milliseconds.
//
// Errors throw std::invalid_argument "<file>:<line>: <what>".
#pragma once

#include "models/ground_motion.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace nsb::scene {

// The standard acceleration of gravity [m/s^2] (3rd CGPM, 1901; NIST SP 811, B.8), the g of a
// COSMOS file in units of g or milli-g, as of a CSV header's [g] (docs/ground-motions.md).
inline constexpr double kStandardGravity = 9.80665;

// One channel of a COSMOS file.
struct CosmosChannel {
  models::Record record;  // t_i = i dt [s], a [m/s^2]
  std::string station;    // network and station codes of text line 5, trimmed ("CE24278")
  std::string station_name;  // text line 5 from column 41, trimmed
  std::string start;      // the record's start, "yyyy-mm-ddThh:mm" ("" when unknown)
  int azimuth = -999;     // integer parameter 54
  bool horizontal = false;   // azimuth 0-360, 500, 501, 600, 601, 700 or 701
  int unit_code = 0;      // integer parameter 3 (COSMOS Table 2)
  double unit = 0.0;      // [m/s^2 per file value] of unit_code
  double dt = 0.0;        // [s]
  std::size_t line = 0;   // line of the channel's first text line, for messages
};

// m/s^2 per value of a COSMOS physical-unit code of acceleration; 0 for any other code.
double cosmos_acceleration_unit(int code);

// True when the file's first line carries the COSMOS format mark "(Format v".
bool is_cosmos_file(const std::filesystem::path&);

// Every channel of a COSMOS V1/V2 file, in file order. Throws std::invalid_argument naming the
// file and line for a malformed header, an unknown or non-acceleration unit, a processing
// stage other than 1 or 2, a missing sampling interval, a count that differs from the data,
// or a non-numeric value.
std::vector<CosmosChannel> read_cosmos(const std::filesystem::path&);

}  // namespace nsb::scene
