// Uniaxial force laws of the bridge's connector parts (docs/bridge.md, "Connectors"), each
// with a committed and a trial state (as takeda::Spring) so that an integrator can retry a
// step or roll back an event:
//   - Cable: a restrainer cable, tension only, with slack and an elastic-perfectly plastic
//     yield in tension (permanent elongation accumulates): the restrainer model of DesRoches
//     & Fenves (2000), J. Struct. Eng. 126(4), and of the Caltrans restrainer design
//     method (evaluated by Saiidi, Maragakis & Feng 1992, CCEER 92-8): a linear
//     tension-only spring with slack.
//   - Law (Kind::kLinear, kBilinear): an elastomeric or lead-rubber bearing in one direction,
//     linear, or bilinear with kinematic hardening (stiffness k, yield force F_y, post-yield
//     stiffness r k; Naeim & Kelly 1999, Design of Seismic Isolated Structures; AASHTO
//     Guide Specifications for Seismic Isolation Design).
//   - Law (Kind::kHyperbolicGap): an abutment backfill, compression only, hyperbolic
//     envelope F = d / (1/K + R_f d / F_ult) (Duncan & Mokwa 2001; Shamsabadi, Rollins &
//     Kapuskar 2007, J. Geotech. Geoenviron. Eng. 133(6)), unloading and reloading on a line
//     of slope K_ur that reaches zero force at a permanent soil deformation, as OpenSees's
//     HyperbolicGapMaterial (Wilson & Elgamal's calibration of the UCSD backwall tests).
//
// Units: kN, m; energies in kJ = kN m.
#pragma once

#include <string>

namespace nsb::models::connectors {

// Restrainer cable: F = 0 while e <= slack + permanent elongation, k (e - slack - e_p) beyond,
// capped at F_y when F_y > 0 (the excess grows e_p).
struct CableParameters {
  double stiffness = 0.0;    // k [kN/m], > 0
  double slack = 0.0;        // s [m], >= 0
  double yield_force = 0.0;  // F_y [kN], >= 0; 0: no yield
  // Throws std::invalid_argument naming the field, prefixed with `prefix`.
  void validate(const std::string& prefix) const;
};

class Cable {
 public:
  explicit Cable(const CableParameters& p) : p_(p) {}
  // Trial elongation beyond the rest length [m] (negative: closer) -> trial tension [kN].
  double set_trial(double elongation);
  double force() const { return trial_.f; }
  double tangent() const { return trial_.tangent; }
  bool tangent_changed() const { return trial_.tangent != committed_.tangent; }
  // The tension at an elongation on the committed state's branch, extended as its tangent
  // line [kN] (as takeda::Spring::force_on_committed_branch). The trial is left as it is.
  double force_on_committed_branch(double elongation) const {
    return committed_.f + committed_.tangent * (elongation - committed_.elongation);
  }
  double stored_energy() const;      // F^2 / (2k) [kJ]
  double dissipated_energy() const;  // F_y times the permanent elongation [kJ]
  double permanent_elongation() const { return trial_.plastic; }
  void commit() { committed_ = trial_; }
  void revert() { trial_ = committed_; }
  const CableParameters& parameters() const { return p_; }

 private:
  struct State {
    double elongation = 0.0, f = 0.0, plastic = 0.0, tangent = 0.0;
  };
  CableParameters p_;
  State committed_, trial_;
};

// One direction of a bearing or a backfill.
enum class Kind { kLinear, kBilinear, kHyperbolicGap };

struct LawParameters {
  Kind kind = Kind::kLinear;
  double stiffness = 0.0;     // k (linear, bilinear) or K_max (hyperbolic) [kN/m], > 0
  double yield_force = 0.0;   // bilinear: F_y [kN], > 0
  double post_yield_ratio = 0.0;  // bilinear: r in [0, 1)
  double ultimate_force = 0.0;    // hyperbolic: F_ult [kN], > 0
  double failure_ratio = 0.0;     // hyperbolic: R_f in (0, 1]
  double unloading_stiffness = 0.0;  // hyperbolic: K_ur [kN/m], >= K_max
  // hyperbolic: +1 the law compresses for d > 0, -1 for d < 0 (the side of the backfill).
  double compression_sign = 1.0;
  void validate(const std::string& prefix) const;
  static LawParameters linear(double k);
  static LawParameters bilinear(double k, double f_yield, double ratio);
  static LawParameters hyperbolic_gap(double k_max, double f_ult, double r_f, double k_ur,
                                      double compression_sign);
};

class Law {
 public:
  explicit Law(const LawParameters& p);
  double set_trial(double d);  // displacement [m] -> force [kN] (positive along +d)
  double force() const { return trial_.f; }
  double tangent() const { return trial_.tangent; }
  double initial_stiffness() const { return p_.stiffness; }
  bool tangent_changed() const { return trial_.tangent != committed_.tangent; }
  // The force at d on the committed state's branch, extended as its tangent line [kN]
  // (as takeda::Spring::force_on_committed_branch). The trial is left as it is.
  double force_on_committed_branch(double d) const {
    return committed_.f + committed_.tangent * (d - committed_.d);
  }
  double stored_energy() const;
  double dissipated_energy() const;
  void commit() { committed_ = trial_; }
  void revert() { trial_ = committed_; }
  const LawParameters& parameters() const { return p_; }
  // Hyperbolic envelope force at compression c >= 0, and its integral from 0 to c.
  double envelope(double c) const;
  double envelope_work(double c) const;

 private:
  struct State {
    double d = 0.0, f = 0.0, tangent = 0.0;
    double back = 0.0;        // bilinear: plastic slip of the elastic-plastic component [m]
    double dissipated = 0.0;  // bilinear: its dissipated energy [kJ]
    double c_max = 0.0;       // hyperbolic: largest compression reached [m]
  };
  void bilinear(State& s, double d) const;
  void hyperbolic(State& s, double d) const;
  LawParameters p_;
  State committed_, trial_;
};

}  // namespace nsb::models::connectors
