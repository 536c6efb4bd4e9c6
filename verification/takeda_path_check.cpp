// Takeda against a hand-derived reference: one displacement path through every rule of the
// trilinear hysteresis of Takeda, Sozen & Nielsen (1970) as implemented (docs/takeda.md,
// rules 1-6 and 9): elastic loading, cracking, the cracked branch, unloading before yield
// (aimed at the other side's cracking point), reloading towards the other side's peak
// (its cracking point, then its furthest cracked-branch point), an inner loop on a reloading
// line, yield, unloading after yield at k_u = k_y' (D_y / D_max)^alpha, reloading towards
// the previous peak beyond yield. The force at every vertex is derived below from the rules,
// in closed form, without the model's code. The path is walked in small steps with a commit
// after each, as an integrator does.
#include "models/takeda.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace tk = nsb::models::takeda;

namespace {

// Spring: k0 = 1000 kN/m, F_c = 10 kN (D_c = 0.01 m), F_y = 30 kN at D_y = 0.05 m,
// r = 0.05, alpha = 0.5. Derived stiffnesses:
//   k_y  = F_y / D_y = 600 kN/m;  k_2 = (F_y - F_c) / (D_y - D_c) = 20 / 0.04 = 500 kN/m;
//   k_p  = r k_y = 30 kN/m;       k_y' = (F_y + F_c) / (D_y + D_c) = 40 / 0.06 = 666.667 kN/m
// (k_y' is Takeda's unloading stiffness at yield: the line from the cracking point of one
// side to the yield point of the other, [T70]).
constexpr double k0 = 1000.0, Fc = 10.0, Dc = 0.01, Fy = 30.0, Dy = 0.05, r = 0.05,
                 alpha = 0.5;
constexpr double k2 = (Fy - Fc) / (Dy - Dc), kp = r * Fy / Dy, kyp = (Fy + Fc) / (Dy + Dc);

// Hand vertices: displacement [m], force [kN], branch the spring is on, and the rule.
struct Vertex {
  double d, f;
  tk::Branch branch;
  const char* rule;
};

std::vector<Vertex> hand_path() {
  using B = tk::Branch;
  std::vector<Vertex> v;
  // V1 rule 1, elastic loading: F = k0 D = 1000 * 0.005 = 5.
  v.push_back({0.005, k0 * 0.005, B::kElastic, "1 elastic"});
  // V2 rule 2, cracking at (0.01, 10), then the cracked branch: 10 + 500 (0.03 - 0.01) = 20.
  // Positive peak x_p+ = 0.03.
  v.push_back({0.03, Fc + k2 * (0.03 - Dc), B::kBackbone, "2 cracked backbone"});
  // V3 rule 4, unloading before yield, aimed at the other side's cracking point (-0.01, -10):
  // k_u+ = (20 + 10) / (0.03 + 0.01) = 750; zero force at D0 = 0.03 - 20/750 = 0.003333.
  // Rule 6 then reloads from (D0, 0) towards the negative side's peak, which has not cracked:
  // its cracking point (-0.01, -10), slope 10 / 0.013333 = 750, the same line. At D = 0:
  // F = -750 * 0.003333 = -2.5.
  const double ku_pos_pre = (20.0 + Fc) / (0.03 + Dc);
  const double d0_a = 0.03 - 20.0 / ku_pos_pre;
  v.push_back({0.0, -ku_pos_pre * d0_a, B::kReloading, "4 unloading before yield, 6 reloading"});
  // V4 rule 2 on the negative side: cracking point reached at -0.01, then the cracked branch
  // to -0.02: F = -(10 + 500 * 0.01) = -15. Negative peak x_p- = 0.02.
  v.push_back({-0.02, -(Fc + k2 * (0.02 - Dc)), B::kBackbone, "2 cracked backbone (-)"});
  // V5 rule 4 on the negative side: k_u- = (15 + 10) / (0.02 + 0.01) = 833.33; zero force at
  // D0 = -0.02 + 15/833.33 = -0.002. Rule 6: reloading towards the positive peak (0.03, 20),
  // slope 20 / 0.032 = 625: at D = 0.01, F = 625 * 0.012 = 7.5.
  const double ku_neg_pre = (15.0 + Fc) / (0.02 + Dc);
  const double d0_b = -0.02 + 15.0 / ku_neg_pre;
  const double kr_b = 20.0 / (0.03 - d0_b);
  v.push_back({0.01, kr_b * (0.01 - d0_b), B::kReloading, "4 (-), 6 reloading to the peak"});
  // V6 rule 9, reversal on the reloading line: unloading at k_u+ = 750 (the positive side's
  // pre-yield slope, peak 0.03) from (0.01, 7.5): at D = 0.004, F = 7.5 - 750 * 0.006 = 3.
  const double f5 = kr_b * (0.01 - d0_b);
  v.push_back({0.004, f5 - ku_pos_pre * (0.01 - 0.004), B::kUnloading, "9 inner loop"});
  // V7 rule 9, the inner loop closes: back along the unloading line to its anchor (0.01, 7.5),
  // then on along the reloading line it left: at D = 0.02, F = 625 * 0.022 = 13.75.
  v.push_back({0.02, kr_b * (0.02 - d0_b), B::kReloading, "9 back on the reloading line"});
  // V8 rules 6 and 3: the reloading line meets the backbone at the peak (0.03, 20), then the
  // cracked branch: F(0.04) = 10 + 500 * 0.03 = 25.
  v.push_back({0.04, Fc + k2 * (0.04 - Dc), B::kBackbone, "3 loading past the peak"});
  // V9 rule 2, yield at (0.05, 30), then post-yield: F(0.07) = 30 + 30 * 0.02 = 30.6.
  v.push_back({0.07, Fy + kp * (0.07 - Dy), B::kBackbone, "2 yield, post-yield"});
  // V10 rule 5, unloading after yield: k_u = k_y' (0.05 / 0.07)^0.5 = 563.436; at D = 0.05:
  // F = 30.6 - 563.436 * 0.02 = 19.331.
  const double f9 = Fy + kp * (0.07 - Dy);
  const double ku_pos_post = kyp * std::pow(Dy / 0.07, alpha);
  v.push_back({0.05, f9 - ku_pos_post * 0.02, B::kUnloading, "5 unloading after yield"});
  // V11 rule 6: zero force at D0 = 0.07 - 30.6/563.436 = 0.015690; reloading towards the
  // negative peak (-0.02, -15) (cracked, not yielded), slope 15 / 0.035690 = 420.28 (below
  // that side's k_u- = 833.33, so rule 8 does not apply); at D = 0: F = -420.28 * 0.015690
  // = -6.594.
  const double d0_c = 0.07 - f9 / ku_pos_post;
  const double kr_c = 15.0 / (d0_c + 0.02);
  v.push_back({0.0, -kr_c * d0_c, B::kReloading, "6 reloading to the cracked peak (-)"});
  // V12 rules 6, 3, 2: the negative peak is reached at -0.02, then the cracked branch to
  // yield (-0.05, -30) and post-yield: F(-0.06) = -(30 + 30 * 0.01) = -30.3.
  v.push_back({-0.06, -(Fy + kp * (0.06 - Dy)), B::kBackbone, "2 yield (-)"});
  // V13 rules 5, 6: k_u- = 666.667 (0.05/0.06)^0.5 = 608.581; zero force at
  // D0 = -0.06 + 30.3/608.581 = -0.010212; reloading towards the positive peak (0.07, 30.6),
  // slope 30.6 / 0.080212 = 381.49: at D = 0.03, F = 381.49 * 0.040212 = 15.340.
  const double f12 = Fy + kp * (0.06 - Dy);
  const double ku_neg_post = kyp * std::pow(Dy / 0.06, alpha);
  const double d0_d = -0.06 + f12 / ku_neg_post;
  const double kr_d = f9 / (0.07 - d0_d);
  v.push_back({0.03, kr_d * (0.03 - d0_d), B::kReloading, "5 (-), 6 reloading to the peak"});
  // V14 rule 6 then 3: through the previous peak (0.07, 30.6) and on along the post-yield
  // branch: F(0.08) = 30 + 30 * 0.03 = 30.9.
  v.push_back({0.08, Fy + kp * (0.08 - Dy), B::kBackbone, "3 past the previous peak"});
  return v;
}

// The branches are straight and the spring walks them exactly: agreement to round-off of
// O(10 kN) forces (measured worst relative deviation: printed below, 1e-14 level).
constexpr double kExact = 1e-10;
// Substeps per leg, as an integrator would commit them.
constexpr int kSubsteps = 97;

}  // namespace

TEST_CASE("takeda: hand-derived trilinear path through every rule") {
  // The quoted numbers of the derivation, reproduced by its closed forms.
  const auto path = hand_path();
  const double quoted[] = {5.0, 20.0, -2.5, -15.0, 7.5, 3.0, 13.75, 25.0, 30.6, 19.331,
                           -6.594, -30.3, 15.340, 30.9};
  REQUIRE(path.size() == std::size(quoted));
  for (std::size_t i = 0; i < path.size(); ++i) {
    CHECK(std::abs(path[i].f - quoted[i]) <= 5e-4 * std::max(1.0, std::abs(quoted[i])));
  }

  tk::Parameters p;
  p.k0 = k0;
  p.f_crack = Fc;
  p.f_yield = Fy;
  p.d_yield = Dy;
  p.post_yield_ratio = r;
  p.unloading_exponent = alpha;
  p.validate();
  tk::Spring s(p);
  double d = 0.0, worst = 0.0;
  for (const auto& v : path) {
    for (int k = 1; k <= kSubsteps; ++k) {
      s.set_trial(d + (v.d - d) * k / kSubsteps);
      s.commit();
    }
    d = v.d;
    const double f = s.force();
    worst = std::max(worst, std::abs(f - v.f) / std::max(1.0, std::abs(v.f)));
    INFO("vertex D = " << v.d << " m, rule " << std::string(v.rule) << ": F = " << f << " kN, hand "
                       << v.f << " kN");
    CHECK(std::abs(f - v.f) <= kExact * std::max(1.0, std::abs(v.f)));
    CHECK(s.committed_state().branch == v.branch);
  }
  std::printf("takeda path: %zu vertices, worst relative force deviation %.2e\n", path.size(),
              worst);
  // Every unloading and reloading slope of the derivation appears as the tangent somewhere:
  // here the last leg, the post-yield branch.
  CHECK(std::abs(s.tangent() - kp) <= kExact * kp);
}
