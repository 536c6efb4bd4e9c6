// Scaling of the scenes' records to a spectral acceleration (model.excitation.scale_to = "sa",
// docs/bridge.md, "Target spectral accelerations"), against computations outside the scene
// reader:
// (a) the record scaled by the factor a scene reports, recomputed by models::response_spectrum
//     at sa_period, has exactly target_sa (and the longitudinal one its longitudinal_sa);
// (b) the benchmark bridge's first natural period, the default sa_period, against the
//     closed-form roots of its 3-DOF eigenproblem assembled by hand from the bent design.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "integrators/system.hpp"
#include "models/ground_motion.hpp"
#include "models/response_spectrum.hpp"
#include "scene/records.hpp"
#include "scene/scene.hpp"

namespace {

namespace fs = std::filesystem;
using nsb::scene::load_scene;
using nsb::models::Record;

const std::string kScene = std::string(NSB_SCENES_DIR) + "/bridge-exc5.toml";
const fs::path kRecords = fs::path(NSB_DATA_DIR) / "ground-motions";

// (a) PSA is linear in the record, and the factor is target / PSA of the unscaled record: the
// rescaled record's PSA differs from the target by the round-off of the recurrence over a few
// thousand steps (measured: <= 1e-15 relative).
constexpr double kScaledSaTolerance = 1e-12;
// (b) Two computations of the same roots in double precision (a quadratic formula against
// Eigen's generalized eigensolver): measured <= 3e-16 relative.
constexpr double kPeriodTolerance = 1e-12;

// PSA [g] of the record scaled by factor, times multiplied by time_scale, at one period.
double scaled_psa(const fs::path& file, double factor, double time_scale, double period,
                  double zeta) {
  Record r = nsb::scene::read_at2(file);
  for (double& a : r.a) a *= factor;
  for (double& t : r.t) t *= time_scale;
  nsb::models::SpectrumOptions o;
  o.damping = zeta;
  o.periods = {period};
  return nsb::models::response_spectrum(r, o).psa_g.front();
}

}  // namespace

TEST_CASE("(a) a record scaled to target_sa has that PSA at sa_period, recomputed") {
  struct Case {
    std::vector<std::string> set;
    double target_sa, longitudinal_sa;  // [g]; longitudinal 0: the common factor
    double time_scale;
  };
  const std::vector<Case> cases = {
      {{"model.excitation.target_sa=0.5"}, 0.5, 0.0, 1.0},
      {{"model.excitation.target_sa=1.2", "model.excitation.sa_period=1.0",
        "model.excitation.sa_damping=0.02", "model.excitation.time_scale=0.5",
        "model.excitation.longitudinal_pga=0", "model.excitation.longitudinal_sa=0.8"},
       1.2,
       0.8,
       0.5},
  };
  for (const auto& c : cases) {
    std::vector<std::string> set = c.set;
    set.insert(set.begin(), "model.excitation.scale_to=sa");
    const auto scene = load_scene(kScene, set);
    REQUIRE(scene.input.transverse);
    REQUIRE(scene.input.longitudinal);
    const auto& tr = *scene.input.transverse;
    INFO("sa_period = " << tr.sa_period);
    const double sa = scaled_psa(kRecords / "RSN988_NORTHR_CCN360.AT2", tr.scale_factor,
                                 c.time_scale, tr.sa_period, tr.sa_damping);
    CHECK(std::abs(sa - c.target_sa) <= kScaledSaTolerance * c.target_sa);
    CHECK(std::abs(tr.sa_g - c.target_sa) <= kScaledSaTolerance * c.target_sa);
    if (c.longitudinal_sa > 0) {
      const auto& lo = *scene.input.longitudinal;
      const double sl = scaled_psa(kRecords / "RSN988_NORTHR_CCN090.AT2", lo.scale_factor,
                                   c.time_scale, lo.sa_period, lo.sa_damping);
      CHECK(std::abs(sl - c.longitudinal_sa) <= kScaledSaTolerance * c.longitudinal_sa);
    }
  }
}

TEST_CASE("(b) the benchmark bridge's first natural period against the hand 3-DOF eigenproblem") {
  // Bents (docs/bridge.md): 2 columns of d = 0.305 m, E = 3e7 kPa, EI_eff = 0.5 E pi d^4 / 64,
  // k = 2 * 12 EI_eff / H^3 for H = 1.83, 2.44, 1.52 m at s = -L/4, 0, +L/4 (L = 33.53 m):
  // k = 24953, 10527, 43545 kN/m. The same springs act along x and y. With q = (x, y, theta),
  //   M = diag(m, m, I),   K0 = [[Sk, 0, 0], [0, Sk, Sks], [0, Sks, Skss]],
  // Sk = sum k_j = 79025 kN/m, Sks = sum k_j s_j = 155852 kN, Skss = sum k_j s_j^2 = 4.813e6 kN m.
  // x decouples: w^2 = Sk / m (T = 0.2649 s). (y, theta): det(K0 - w^2 M) = 0 is
  //   m I w^4 - (Sk I + Skss m) w^2 + (Sk Skss - Sks^2) = 0,
  // whose smaller root w^2 = 314.44 s^-2 gives T1 = 0.35433 s, the longest of the three.
  const double pi = std::numbers::pi;
  const double m = 140.5, inertia = 13090.0, length = 33.53;
  const double ei = 0.5 * 3.0e7 * pi * std::pow(0.305, 4) / 64.0;
  const double heights[] = {1.83, 2.44, 1.52};
  const double positions[] = {-length / 4, 0.0, length / 4};
  double sk = 0, sks = 0, skss = 0;
  for (int j = 0; j < 3; ++j) {
    const double k = 2 * 12 * ei / std::pow(heights[j], 3);
    sk += k;
    sks += k * positions[j];
    skss += k * positions[j] * positions[j];
  }
  const double a = m * inertia, b = -(sk * inertia + skss * m), c = sk * skss - sks * sks;
  const double w2_low = (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
  const double w2_x = sk / m;
  const double t1 = 2 * pi / std::sqrt(std::min(w2_low, w2_x));
  CHECK(t1 == doctest::Approx(0.35433).epsilon(1e-4));  // the value in the comment above

  auto scene =
      load_scene(kScene, {"model.excitation.scale_to=sa", "model.excitation.target_sa=0.5"});
  const std::vector<double> periods = nsb::integrators::natural_periods(*scene.system);
  REQUIRE(periods.size() == 3);
  CHECK(std::abs(periods.front() - t1) <= kPeriodTolerance * t1);
  CHECK(std::abs(scene.input.transverse->sa_period - t1) <= kPeriodTolerance * t1);
  // The shortest period is the trust check's (runs/trust.hpp): the larger (y, theta) root.
  const double w2_high = (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
  const double t3 = 2 * pi / std::sqrt(std::max(w2_high, w2_x));
  CHECK(std::abs(periods.back() - t3) <= kPeriodTolerance * t3);
}
