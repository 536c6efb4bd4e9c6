// Takeda hysteresis for reinforced-concrete piers: one uniaxial spring with a committed and a
// trial state, so that an integrator can retry a step or roll back an event.
//
// Backbone: trilinear (cracking, yield, post-yield; Takeda, Sozen & Nielsen 1970) or, when
// f_crack = 0, bilinear (the modified Takeda model of Otani 1974 and Emori & Schnobrich 1978).
// Unloading stiffness after yield k_u = k_y (D_y / D_max)^alpha; reloading aims at the
// previous extreme (peak) point of the other side: its yield point while that side has not
// yielded (bilinear), or its furthest cracked-branch point (trilinear, as Takeda et al.).
// The full rule set, its sources and where it departs from them: docs/takeda.md.
//
// Units: kN, m; energies in kJ = kN m.
#pragma once

#include <algorithm>
#include <cmath>

namespace nsb::models::takeda {

// Two tangents differing by less than this (relative) are the same branch slope.
inline constexpr double kTangentChangeTolerance = 1e-12;

struct Parameters {
  double k0 = 0.0;                  // initial (uncracked) stiffness [kN/m], > 0
  double f_crack = 0.0;             // cracking force [kN]; 0 selects the bilinear variant
  double f_yield = 0.0;             // yield force [kN], > f_crack
  double d_yield = 0.0;             // yield displacement [m], > 0
  double post_yield_ratio = 0.05;   // post-yield stiffness / k_y, with k_y = f_yield/d_yield
  double unloading_exponent = 0.4;  // alpha in k_u = k_y (d_y / d_max)^alpha, in [0, 1]
  // Throws std::invalid_argument naming the field. Besides the ranges above: the trilinear
  // variant needs k0 > f_yield/d_yield (cracking before yield) and a post-yield stiffness
  // below the cracked stiffness; the bilinear variant needs k0 = f_yield/d_yield.
  void validate() const;
  // Bilinear (modified Takeda, Otani / Emori–Schnobrich): k0 = f_yield / d_yield.
  static Parameters bilinear(double f_yield, double d_yield, double post_yield_ratio = 0.05,
                             double unloading_exponent = 0.4);
};

// Which rule the spring follows (docs/takeda.md numbers them).
enum class Branch {
  kElastic,   // initial linear branch, never left: F = k0 D
  kBackbone,  // on the backbone (skeleton) curve on side `side`
  kUnloading, // straight unloading line of slope k_u towards zero force
  kReloading, // straight reloading line from zero force towards the target of side `side`
};

// Everything the spring remembers. Sides: +1 positive, -1 negative displacement/force.
struct State {
  double d = 0.0;            // displacement [m]
  double f = 0.0;            // force [kN]
  Branch branch = Branch::kElastic;
  int side = 1;              // side of the current branch (sign of its force)
  double peak_pos_d = 0.0;   // furthest backbone point reached on the positive side [m]
  double peak_neg_d = 0.0;   // same on the negative side (<= 0) [m]
  // Current straight branch (unloading or reloading): F = line_f + line_k (D - line_d).
  double line_d = 0.0, line_f = 0.0, line_k = 0.0;
  double line_end_d = 0.0;   // reloading: displacement where the line meets the backbone
  // Unloading that started on a reloading line returns to it past its anchor.
  bool parent_reloading = false;
  double parent_d = 0.0, parent_f = 0.0, parent_k = 0.0, parent_end_d = 0.0;
  double work = 0.0;         // work done on the spring, integral of F dD [kJ]
};

class Spring {  // one uniaxial Takeda spring with committed and trial state
 public:
  explicit Spring(const Parameters& p);
  // Trial displacement [m] -> trial force [kN]. A non-finite d (a diverged integration)
  // gives a NaN force, tangent and energy instead of throwing; revert() recovers.
  double set_trial(double d);
  double force() const { return trial_.f; }        // trial force
  double tangent() const { return trial_tangent_; }  // trial tangent stiffness [kN/m]
  // The force at d on the committed state's branch, extended as its tangent line:
  // committed force + committed tangent (d - committed d) [kN]. The trial is left as it is.
  double force_on_committed_branch(double d) const {
    return committed_.f + committed_tangent_ * (d - committed_.d);
  }
  bool tangent_changed() const {       // trial tangent differs from the committed one
    return std::abs(trial_tangent_ - committed_tangent_) >
           kTangentChangeTolerance * std::max(std::abs(committed_tangent_), k_elastic_);
  }
  bool elastic() const;                // never left its initial branch (committed state)
  double stored_energy() const;        // recoverable elastic energy at trial state [kJ]
  double dissipated_energy() const;    // hysteretic energy dissipated up to trial state [kJ]
  void commit();
  void revert();
  const Parameters& parameters() const;

  // Additions beyond the agreed interface, for tests and diagnostics.
  double displacement() const { return trial_.d; }  // trial displacement [m]
  const State& trial_state() const { return trial_; }
  const State& committed_state() const { return committed_; }
  double backbone(double d) const;             // monotonic (skeleton) force at d [kN]
  double unloading_stiffness(int side, double peak_d) const;  // k_u for a peak [kN/m]
  // The state reached from `from` by a move to d under the general rules (the branch logic
  // that set_trial() skips for a move along the current straight branch).
  State moved(const State& from, double d) const;

 private:
  double backbone_magnitude(double x) const;   // b(x), x >= 0
  double backbone_integral(double x) const;    // integral_0^x b, x >= 0
  double backbone_slope(double x) const;       // left slope of b at x
  double backbone_slope_right(double x) const; // right slope of b at x
  static double peak_magnitude(const State& s, int side);
  void start_reloading(State& s, int side) const;
  double reloading_meets_backbone(double x0, double k) const;
  static void move_on_line(State& s, double d_new, double f_new);
  // True when a move of the committed state to d != committed_.d stays on its straight
  // branch (initial elastic, unloading or reloading line); f is then the force at d.
  bool stays_on_branch(double d, double& f) const;
  void advance(State& s, double d) const;
  // One move of advance() on the branch of s in direction m = +-1: true if d is reached there,
  // false if s has moved to the end of the branch and switched to the next one.
  bool move_on_elastic(State& s, double d, int m) const;    // rule 1
  bool move_on_backbone(State& s, double d, int m) const;   // rules 2-5
  bool move_on_unloading(State& s, double d, int m) const;  // rules 6, 9
  bool move_on_reloading(State& s, double d, int m) const;  // rules 6-9
  double tangent_of(const State& s) const;

  Parameters p_;
  double k_elastic_ = 0.0; // initial stiffness (k0, or exactly f_yield/d_yield if bilinear)
  double d_crack_ = 0.0;   // cracking displacement (= d_yield for the bilinear variant)
  double f_crack_ = 0.0;   // cracking force (= f_yield for the bilinear variant)
  double k_crack_ = 0.0;   // cracked-branch stiffness (= k_y for the bilinear variant)
  double k_post_ = 0.0;    // post-yield stiffness
  double k_yield_unload_ = 0.0;  // Takeda's k_y of the unloading rule
  State committed_;
  State trial_;
  double trial_tangent_ = 0.0;
  double committed_tangent_ = 0.0;
  // trial_ equals committed_ except possibly in d, f and work (the fields a move along a
  // straight branch changes), so that commit() and revert() copy only those.
  bool trial_moved_on_branch_ = true;
};

}  // namespace nsb::models::takeda
