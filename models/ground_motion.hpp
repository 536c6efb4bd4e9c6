// Ground-motion records and the smooth support motion built from them.
//
// A Record is the raw sampled acceleration. A GroundMotion turns it into a C2 motion:
// the acceleration is the natural cubic spline (GSL) through the samples, the velocity and
// displacement are its exact integrals (piecewise quartic and quintic), optionally corrected
// by a least-squares polynomial baseline so that the motion ends at rest. Several supports
// are several GroundMotion objects, each with its own record or delay (wave passage). A
// sequence of records (a mainshock and its aftershocks) is one GroundMotion made of the
// motions of its records, each delayed to its place in the sequence (GroundMotion::sequence).
// The record files are read by scene/records.hpp. Formats, units, scaling, the baseline method
// and the time compression: docs/ground-motions.md.
//
// Units: m, s, m/s^2.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace nsb::models {

struct Record {
  std::vector<double> t;  // sample times [s], strictly increasing
  std::vector<double> a;  // ground acceleration [m/s^2]
  std::string source;     // file it was read from (or a description)
};

// A cubic spline needs three samples (GSL's cspline minimum size).
inline constexpr std::size_t kMinRecordSamples = 3;

// Checks a record built in code: equal sizes, at least 3 samples, finite values, strictly
// increasing time. Throws std::invalid_argument naming the record's source and the sample.
void validate_record(const Record&);

struct GroundMotionOptions {
  double target_pga = 0.0;     // [m/s^2], >= 0; 0 keeps the record's amplitude
  double scale = 1.0;          // factor applied after target_pga scaling, finite
  double time_scale = 1.0;     // similitude: t -> time_scale * t (0.5 for 1/4 length scale), > 0
  bool baseline_correction = true;  // remove drift so that final velocity and displacement ~ 0
  double delay = 0.0;          // wave-passage delay [s], >= 0: motion(t) = motion(t - delay)
  void validate() const;       // throws std::invalid_argument naming the field
};

class GroundMotion {  // smooth (GSL cubic spline) displacement, velocity, acceleration at any t
 public:
  GroundMotion() = default;    // zero motion
  GroundMotion(const Record& r, const GroundMotionOptions& o = {});
  // The concatenation of `parts` in time (docs/ground-motions.md, "Sequences"): each part a
  // record's motion already delayed to its place, in order, part k + 1 starting at or after
  // the end of part k (empty parts are skipped). At t the motion is that of the last part
  // started before t (the first before any has; at its start time a part's first sample is
  // not yet used, the part before it holds): its acceleration and velocity are zero between
  // parts (a rest interval) and its displacement is held. The ground does not jump at the
  // start of a part: part k starts from the displacement at which the parts before it left
  // the ground, the sum of their final displacements, or exactly 0 when `ends_at_rest` (every
  // part baseline corrected, so that each ends at rest where it started, up to round-off,
  // which is then dropped). A sequence of one part is that part. Throws
  // std::invalid_argument when no part is given or parts overlap in time.
  static GroundMotion sequence(const std::vector<GroundMotion>& parts, bool ends_at_rest);
  double displacement(double t) const;  // [m]; 0 before start; held after end
  double velocity(double t) const;      // [m/s]; 0 before start and after end
  double acceleration(double t) const;  // [m/s^2]; 0 before start and after end
  // All three at t, from one interval search and one baseline evaluation: the same numbers
  // as displacement(t), velocity(t) and acceleration(t).
  struct Values {
    double displacement = 0.0;  // [m]
    double velocity = 0.0;      // [m/s]
    double acceleration = 0.0;  // [m/s^2]
  };
  Values values(double t) const;
  double duration() const;              // [s], after time scaling (a sequence: first start
                                        //   to last end)
  double pga() const;                   // [m/s^2], max |a| over the samples after scaling
                                        //   (a sequence: over its parts)

  // Additions beyond the agreed interface.
  double start_time() const;            // first sample time, after time scaling and delay [s]
  double end_time() const;              // last sample time, after time scaling and delay [s]
  const std::string& source() const;    // the record's source (a sequence: " then "-joined)
  bool empty() const { return data_ == nullptr; }

  struct Data;  // immutable, shared between copies (defined in ground_motion.cpp)

 private:
  // The parts of a sequence and the displacement each starts from [m]; null for one record.
  struct Parts;
  Values sequence_values(double t) const;

  std::shared_ptr<const Data> data_;  // the record's (a sequence: its first part's)
  std::shared_ptr<const Parts> parts_;
};

}  // namespace nsb::models
