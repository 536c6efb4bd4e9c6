// Bents with their columns ([[model.bents]] column_offsets, skew_deg; models/parts.hpp, Bent):
// the first torsional period of a rigid deck on two skewed two-column bents against the closed
// form of docs/bridge.md ("Bents with their columns"), the forces against the stiffness, and
// the checks of the keys.
#include "scene/scene.hpp"
#include "scene/test/scene_files.hpp"

#include "models/assembly.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace {

using nsb::scene::load_scene;
using nsb::scene::test_files::error_of;
using nsb::scene::test_files::write;

// A 90 m deck of 1500 t on two bents at +-22.5 m, each of two columns 6 m apart and skewed by
// 20 deg; explicit spring values so that the closed form reads them directly.
constexpr double kMass = 1500.0, kInertia = 1.5e6;    // [t], [t m^2]
constexpr double kPosition = 22.5, kOffset = 3.0;     // s, e [m]
constexpr double kSkewDeg = 20.0;                     // beta [deg]
constexpr double kLongitudinal = 40000.0, kTransverse = 60000.0;  // whole bent [kN/m]

std::string bent(double position, const std::string& columns) {
  return "[[model.bents]]\nposition = " + std::to_string(position) +
         "\ncolumns = 2\nstiffness_longitudinal = 40000.0\nyield_force_longitudinal = 400.0\n"
         "stiffness_transverse = 60000.0\nyield_force_transverse = 600.0\n" + columns;
}

std::string scene(const std::string& columns) {
  return R"([model]
kind = "bridge"
[model.deck]
mass = 1500.0
inertia = 1.5e6
length = 90.0
width = 12.0
[model.gaps]
left = 0.05
right = 0.05
)" + bent(-kPosition, columns) + bent(kPosition, columns) + R"(
[solver]
method = "moreau"
end_time = 0.1
step = 1.0e-3
)";
}

const std::string kColumns = "column_offsets = [-3.0, 3.0]\nskew_deg = 20.0\n";

}  // namespace

TEST_CASE("bents with columns: the first torsional period is the closed form's") {
  auto s = load_scene(write("columns.toml", scene(kColumns)));
  auto* a = dynamic_cast<nsb::models::Assembly*>(s.system.get());
  REQUIRE(a != nullptr);
  // docs/bridge.md, "Bents with their columns": column c of bent j carries k_x,j / n and
  // k_y,j / n; the symmetric layout (s = +-a, e = +-b, one beta) decouples theta, and
  //   k_theta = sum_j sum_c [ k_x,j/n (s_j sin beta + e_c / cos beta)^2
  //                         + k_y,j/n (s_j cos beta)^2 ],   T_theta = 2 pi sqrt(I_d / k_theta).
  const double beta = kSkewDeg * std::numbers::pi / 180.0;
  double k_theta = 0.0;
  for (const double sj : {-kPosition, kPosition}) {
    for (const double e : {-kOffset, kOffset}) {
      const double lever_n = sj * std::sin(beta) + e / std::cos(beta);
      const double lever_t = sj * std::cos(beta);
      k_theta += 0.5 * kLongitudinal * lever_n * lever_n + 0.5 * kTransverse * lever_t * lever_t;
    }
  }
  const double closed = 2.0 * std::numbers::pi * std::sqrt(kInertia / k_theta);
  // Mode 1: k_theta / I_d = 39.7 rad^2/s^2 lies below both translational omega^2, which are
  // >= the smaller eigenvalue of the x-y block over m, 2 min(k_x, k_y) / m = 53.3 rad^2/s^2.
  const double omega1 = a->rayleigh_damping().omega(0);
  const double period = 2.0 * std::numbers::pi / omega1;
  // 1e-9 relative: the eigen-solver's rounding on a 3x3 of condition ~1e5 is ~1e-12.
  CHECK(std::abs(period - closed) <= 1e-9 * closed);
  // Without its columns' offsets the same bents resist twist by their levers s sin(beta) and
  // s cos(beta) alone: k_theta loses sum_j k_x,j (b / cos beta)^2 = 8.15e5 kN m of 5.92e7,
  // and the period, 0.7 % longer, is again the closed form's.
  auto axis = load_scene(write("axis.toml", scene("skew_deg = 20.0\n")));
  auto* b = dynamic_cast<nsb::models::Assembly*>(axis.system.get());
  REQUIRE(b != nullptr);
  double k_axis = 0.0;
  for (const double sj : {-kPosition, kPosition}) {
    const double lever_n = sj * std::sin(beta), lever_t = sj * std::cos(beta);
    k_axis += kLongitudinal * lever_n * lever_n + kTransverse * lever_t * lever_t;
  }
  const double closed_axis = 2.0 * std::numbers::pi * std::sqrt(kInertia / k_axis);
  const double period_axis = 2.0 * std::numbers::pi / b->rayleigh_damping().omega(0);
  CHECK(std::abs(period_axis - closed_axis) <= 1e-9 * closed_axis);
  CHECK(period_axis > 1.005 * period);
}

TEST_CASE("bents with columns: the forces are -K0 q in the elastic range, with every coupling") {
  // An asymmetric layout (offsets -2 and 5 m) couples x, y and theta; the forces at a small
  // displacement (well inside the yield displacements of 1 cm) must be -K0 q.
  auto s = load_scene(write("coupled.toml", scene("column_offsets = [-2.0, 5.0]\nskew_deg = 20.0\n")));
  auto* a = dynamic_cast<nsb::models::Assembly*>(s.system.get());
  REQUIRE(a != nullptr);
  nsb::integrators::Vector q(3), u = nsb::integrators::Vector::Zero(3), f(3);
  q << 1e-4, -2e-4, 3e-6;
  a->forces(0.0, q, u, f);
  const nsb::integrators::Vector expected = -a->initial_stiffness() * q;
  for (int i = 0; i < 3; ++i) {
    CHECK(f(i) == doctest::Approx(expected(i)).epsilon(1e-12).scale(1.0));
  }
  // K0's coupling x-theta: sum over columns of k_x/n n_x lever_n + k_y/n t_x lever_t, with
  // n_x lever_n = -(s sin(beta) cos(beta) + e) and t_x lever_t = s sin(beta) cos(beta); the
  // +-s terms cancel, leaving -k_x/2 (e_1 + e_2) per bent, times 2 bents.
  const double k_xtheta = -0.5 * kLongitudinal * (-2.0 + 5.0) * 2.0;
  CHECK(a->initial_stiffness()(0, 2) == doctest::Approx(k_xtheta).epsilon(1e-12));
}

TEST_CASE("bents with columns: one offset per column, named at the key") {
  const std::string e = error_of("count.toml", scene("column_offsets = [1.0]\n"));
  CHECK(e.find("count.toml:") != std::string::npos);
  CHECK(e.find("model.bents[0].column_offsets: must give one offset per column: 1 offsets for "
               "columns = 2") != std::string::npos);
  const std::string k = error_of("skew.toml", scene("skew_deg = 85.0\n"));
  CHECK(k.find("model.bents[0].skew_deg") != std::string::npos);
}

TEST_CASE("bents with columns: the bents group reports each bent's mean deformation and summed "
          "force, as computed by hand") {
  // Two columns at e = -3 and +3 m, no skew (beta = 0): column c of the bent at s sits at
  // r_c = (s, e_c) and deforms along x by delta_x = x - e_c theta and along y by
  // delta_y = y + s theta (models/parts.hpp, Bent, with n = (1, 0), t = (0, 1)); it carries
  // half of each spring, k_x/2 = 20000 kN/m and k_y/2 = 30000 kN/m, elastic here (every
  // column force below 40 kN, the column yield forces 200 and 300 kN).
  // State: x = 1e-4 m, y = -2e-4 m, theta = 2e-5 rad; the columns, by hand:
  //   both bents, e = -3: delta_x = 1e-4 + 6e-5 = 1.6e-4, F_x = 20000 * 1.6e-4 = 3.2 kN;
  //               e = +3: delta_x = 1e-4 - 6e-5 = 4e-5,   F_x = 0.8 kN;
  //   bent 1 (s = -22.5): delta_y = -2e-4 - 4.5e-4 = -6.5e-4, F_y = -19.5 kN per column;
  //   bent 2 (s = +22.5): delta_y = -2e-4 + 4.5e-4 = 2.5e-4,  F_y = 7.5 kN per column.
  // The bent's columns: ux, uy the mean deformations, fx, fy minus the summed forces (the
  // force on the deck):
  //   bent 1: ux = 1e-4, uy = -6.5e-4, fx = -(3.2 + 0.8) = -4, fy = +39;
  //   bent 2: ux = 1e-4, uy = 2.5e-4,  fx = -4,               fy = -15.
  auto s = load_scene(write("hand.toml", scene("column_offsets = [-3.0, 3.0]\n")));
  auto* a = dynamic_cast<nsb::models::Assembly*>(s.system.get());
  REQUIRE(a != nullptr);
  using nsb::integrators::OutputGroup;
  const std::vector<std::string> names = a->output_columns(OutputGroup::kBents);
  REQUIRE(names == std::vector<std::string>{"bent1_ux", "bent1_uy", "bent1_fx", "bent1_fy",
                                            "bent2_ux", "bent2_uy", "bent2_fx", "bent2_fy"});
  nsb::integrators::Vector q(3), u = nsb::integrators::Vector::Zero(3), f(3);
  q << 1e-4, -2e-4, 2e-5;
  std::vector<double> out(names.size());
  a->output_values(OutputGroup::kBents, 0.0, q, u, out.data());
  const double expected[] = {1e-4, -6.5e-4, -4.0, 39.0, 1e-4, 2.5e-4, -4.0, -15.0};
  for (std::size_t k = 0; k < names.size(); ++k) {
    INFO(names[k]);
    // 1e-12 relative: a handful of products and sums of numbers of order one.
    CHECK(out[k] == doctest::Approx(expected[k]).epsilon(1e-12).scale(1e-6));
  }
  // Each column's own force, seen in the moment on the deck: f_theta = -sum_c F_c J_c,theta
  // with J_x,theta = -e_c and J_y,theta = s, so
  //   sum F J = 2 bents x (3.2 * 3 + 0.8 * (-3)) + 2 x (-19.5)(-22.5) + 2 x 7.5 x 22.5
  //           = 14.4 + 877.5 + 337.5 = 1229.4 kN m,
  // where equal columns (no offsets) would give the x springs no moment.
  a->forces(0.0, q, u, f);
  CHECK(f(2) == doctest::Approx(-1229.4).epsilon(1e-12));
  CHECK(f(0) == doctest::Approx(-8.0).epsilon(1e-12));
  CHECK(f(1) == doctest::Approx(39.0 - 15.0).epsilon(1e-12));
}
