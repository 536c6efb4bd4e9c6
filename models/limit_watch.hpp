// The limit states an assembled bridge watches over a run (docs/limit-states.md): loss of seat
// (unseating) at the abutments and hinges, closure of the joints, the bents' drift ratio and
// the deck's residual rotation. What to watch is part of the assembly's parts
// (Assembly::Parts::limits); the state is sized once, and watching a step allocates nothing.
//
// Definitions (docs/limit-states.md gives the sources):
//   joint j with corner contacts c: opening o_j(t) = max_c g_N,c(t), smallest gap
//     m_j(t) = min_c g_N,c(t);
//   unseating: overlap = seat_length - o_j, exceeded when overlap < 0 (the end has moved off
//     its seat; the run stops); margin = the smallest overlap [m];
//   closure: exceeded at the first step with m_j <= 0 or a positive normal impulse of one of
//     its contacts (the joint closed: pounding); margin = the smallest m_j [m];
//   drift of bent b: r_b = |(dx, dy)| / H_b, (dx, dy) the bent top's displacement relative to
//     its support; exceeded when r_b >= drift_ratio; margin = drift_ratio - max r_b [-];
//   residual rotation of body i: |theta_i| at the last accepted step against the limit;
//     margin = limit - |theta_i(t_end)| [rad].
//
// Units: m, s, rad.
#pragma once

#include "integrators/system.hpp"

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace nsb::models {

// One joint between a deck end and what carries it: an abutment seat or the next frame.
struct JointLimit {
  std::string name;               // "left", "right" or "hinge_<k>" (1-based)
  std::array<int, 2> contacts{};  // 0-based indices of the joint's two corner contacts
  double seat_length = std::numeric_limits<double>::infinity();  // [m]; finite: unseating
  bool closure = true;            // watch the joint's closure
};

// What an assembly watches; empty (the default) watches nothing.
struct LimitSpec {
  std::vector<JointLimit> joints;
  std::vector<double> bent_heights;  // H of each bent [m] (Assembly::Parts::bents order);
                                     //   needed for every bent when drift_ratio > 0
  double drift_ratio = 0.0;          // [-]; 0: the drift is not watched
  double residual_rotation = 0.0;    // [rad]; 0: the residual rotation is not watched
  int deck_bodies = 0;               // bodies 0 .. deck_bodies - 1 are the deck's segments,
                                     //   whose residual rotation is watched; 0: every body
                                     //   (a backfill abutment's backwall is a body too)
  bool empty() const {
    return joints.empty() && drift_ratio == 0.0 && residual_rotation == 0.0;
  }
  // Throws std::invalid_argument naming the field ("limits.joints[1].contacts: ...") for
  // contact indices outside [0, contacts), a bad seat length or limit, or missing heights.
  void validate(int contacts, int bents, int bodies) const;
};

// The running extremes of the watched quantities. Fixed size after construction.
class LimitWatch {
 public:
  LimitWatch() = default;
  LimitWatch(LimitSpec spec, int bodies);

  const LimitSpec& spec() const { return spec_; }
  bool empty() const { return spec_.empty(); }
  bool watches_joints() const { return !spec_.joints.empty(); }
  bool watches_drift() const { return spec_.drift_ratio > 0.0; }

  // The gaps g_N of every contact at t and the step's normal impulses (null: none known);
  // true when a seat is lost at this step (the first time only).
  bool joints(double t, const std::vector<double>& gaps, const integrators::Vector* impulse);
  // Bent b's top displacement relative to its support (dx, dy) [m] at t.
  void drift(double t, std::size_t b, double dx, double dy);
  // The generalized coordinates at the end of an accepted step at t.
  void end_state(double t, const integrators::Vector& q);

  // The limit states in the order: per joint unseating, closure; per bent drift; per body
  // residual rotation.
  std::vector<integrators::LimitStateValue> values() const;

 private:
  struct Joint {
    double min_overlap = std::numeric_limits<double>::infinity();
    double unseat_time = std::numeric_limits<double>::quiet_NaN();
    double min_gap = std::numeric_limits<double>::infinity();
    double closure_time = std::numeric_limits<double>::quiet_NaN();
  };
  struct Drift {
    double peak = 0.0;
    double time = std::numeric_limits<double>::quiet_NaN();
  };

  LimitSpec spec_;
  std::vector<Joint> joints_;
  std::vector<Drift> drifts_;
  std::vector<double> theta_end_;  // |theta| of each body at t_end_
  double t_end_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace nsb::models
