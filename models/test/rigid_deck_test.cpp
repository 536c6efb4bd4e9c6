// The free planar deck between two fixed abutments, a bridge design without bents built as an
// assembly of one body (models/bridge_parts.hpp): geometry, numbering, directions and input
// checks (the convention is in docs/bridge.md).
#include "models/bridge_parts.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace {

using nsb::models::Assembly;
using nsb::models::BridgeDesign;

// Geometry is evaluated with a handful of trigonometric operations on O(10 m) numbers.
constexpr double kGeomTol = 1e-12;
// Central differences, step 1e-6 on a 30 m deck: truncation ~ h^2 * L ~ 3e-11, round-off
// ~ 1e-16 * 30 / 1e-6 ~ 3e-9.
constexpr double kFdStep = 1e-6;
constexpr double kFdTol = 1e-7;

BridgeDesign deck(double skew_deg) {
  BridgeDesign p = BridgeDesign::free_deck();
  p.mass = 140.5;
  p.inertia = 13090.0;
  p.deck = {.length = 33.35, .width = 2.44, .skew_deg = skew_deg, .gap_right = 0.02,
            .gap_left = 0.03};
  p.restitution = 0.3;
  p.friction = 0.5;
  return p;
}

Assembly free_deck(const BridgeDesign& p) { return Assembly(nsb::models::bridge_parts(p)); }

std::string error_of(const BridgeDesign& p) {
  try {
    free_deck(p);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST_CASE("reference gaps are gap * cos(alpha) and the coefficients are passed through") {
  for (double skew : {0.0, 15.0, 30.0, -20.0}) {
    Assembly d = free_deck(deck(skew));
    auto c = d.make_contact_buffer();
    d.contact_data(0.0, d.initial_position(), d.initial_velocity(), c);
    const double ca = std::cos(skew * std::numbers::pi / 180.0);
    CHECK(c[0].gap_normal == doctest::Approx(0.03 * ca).epsilon(kGeomTol));
    CHECK(c[1].gap_normal == doctest::Approx(0.03 * ca).epsilon(kGeomTol));
    CHECK(c[2].gap_normal == doctest::Approx(0.02 * ca).epsilon(kGeomTol));
    CHECK(c[3].gap_normal == doctest::Approx(0.02 * ca).epsilon(kGeomTol));
    for (const auto& ci : c) {
      CHECK(ci.restitution == 0.3);
      CHECK(ci.friction == 0.5);
      CHECK(!ci.far);
      CHECK(ci.what_normal == 0.0);  // fixed abutments
      CHECK(ci.wbar_normal == 0.0);  // at rest, no rotation rate
    }
  }
}

TEST_CASE("straight deck: W_N and W_T of contacts 1..4 derived by hand") {
  // Corners (+-L/2, +-W/2). Right face normal n = (-1, 0), tangent t = n rotated +90 deg =
  // (0, -1); left face n = (1, 0), t = (0, 1). W_N = (n, r x n), W_T = (t, r x t):
  //   1: r = (-L/2,  W/2): W_N = ( 1, 0, -W/2), W_T = (0,  1, -L/2)
  //   2: r = (-L/2, -W/2): W_N = ( 1, 0,  W/2), W_T = (0,  1, -L/2)
  //   3: r = ( L/2,  W/2): W_N = (-1, 0,  W/2), W_T = (0, -1, -L/2)
  //   4: r = ( L/2, -W/2): W_N = (-1, 0, -W/2), W_T = (0, -1, -L/2)
  // Check of 3: a counter-clockwise rotation moves corner 3 by dtheta (-W/2, L/2), away from
  // the right face: the gap opens by (W/2) dtheta.
  Assembly d = free_deck(deck(0.0));
  auto c = d.make_contact_buffer();
  d.contact_data(0.0, d.initial_position(), d.initial_velocity(), c);
  const double hl = 33.35 / 2, hw = 2.44 / 2;
  const double wn[4][3] = {{1, 0, -hw}, {1, 0, hw}, {-1, 0, hw}, {-1, 0, -hw}};
  const double wt[4][3] = {{0, 1, -hl}, {0, 1, -hl}, {0, -1, -hl}, {0, -1, -hl}};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 3; ++j) {
      CHECK(c[static_cast<std::size_t>(i)].w_normal(j) == doctest::Approx(wn[i][j]).epsilon(kGeomTol));
      CHECK(c[static_cast<std::size_t>(i)].w_tangent(j) == doctest::Approx(wt[i][j]).epsilon(kGeomTol));
    }
  }
}

TEST_CASE("W_N is the gradient of g_N for a skewed, displaced, rotated deck") {
  Assembly d = free_deck(deck(30.0));
  auto c = d.make_contact_buffer(), cp = c, cm = c;
  const nsb::integrators::Vector q = Eigen::Vector3d(-0.005, 0.3, 0.002);
  const nsb::integrators::Vector u = Eigen::Vector3d::Zero();
  d.contact_data(0.0, q, u, c);
  for (int j = 0; j < 3; ++j) {
    nsb::integrators::Vector qp = q, qm = q;
    qp(j) += kFdStep;
    qm(j) -= kFdStep;
    d.contact_data(0.0, qp, u, cp);
    d.contact_data(0.0, qm, u, cm);
    for (std::size_t i = 0; i < 4; ++i) {
      const double fd = (cp[i].gap_normal - cm[i].gap_normal) / (2 * kFdStep);
      CHECK(c[i].w_normal(j) == doctest::Approx(fd).epsilon(kFdTol).scale(1.0));
    }
  }
}

TEST_CASE("a translation along the axis closes the right gaps and opens the left ones") {
  // Skew 30 deg: moving the deck by dx along +x changes the right normal gaps by
  // -dx cos(alpha) and the left ones by +dx cos(alpha).
  Assembly d = free_deck(deck(30.0));
  auto c = d.make_contact_buffer();
  const double dx = 0.01, ca = std::cos(std::numbers::pi / 6);
  d.contact_data(0.0, Eigen::Vector3d(dx, 0, 0), Eigen::Vector3d::Zero(), c);
  CHECK(c[0].gap_normal == doctest::Approx((0.03 + dx) * ca).epsilon(kGeomTol));
  CHECK(c[2].gap_normal == doctest::Approx((0.02 - dx) * ca).epsilon(kGeomTol));
  CHECK(c[3].gap_normal == doctest::Approx((0.02 - dx) * ca).epsilon(kGeomTol));
}

TEST_CASE("a contact far from its abutment and not approaching fast is flagged far") {
  Assembly d = free_deck(deck(0.0));
  auto c = d.make_contact_buffer();
  // x = -0.5: right gaps 0.52 m (far), left ones penetrated (not far).
  d.contact_data(0.0, Eigen::Vector3d(-0.5, 0, 0), Eigen::Vector3d::Zero(), c);
  CHECK(c[2].far);
  CHECK(c[3].far);
  CHECK(!c[0].far);
  // Approaching the right abutment at 10 m/s: 0.52 m closes within 0.1 s -> not far.
  d.contact_data(0.0, Eigen::Vector3d(-0.5, 0, 0), Eigen::Vector3d(10, 0, 0), c);
  CHECK(!c[2].far);
}

TEST_CASE("no forces, no stiffness, no damping, no energy: the deck is free between impacts") {
  Assembly d = free_deck(deck(10.0));
  nsb::integrators::Vector f = Eigen::Vector3d::Constant(1.0);
  d.forces(0.0, d.initial_position(), Eigen::Vector3d(1, 2, 3), f);
  CHECK(f.norm() == 0.0);
  CHECK(d.mass()(0, 0) == 140.5);
  CHECK(d.mass()(2, 2) == 13090.0);
  CHECK(d.energy(0.0, d.initial_position()).stored == 0.0);
  nsb::integrators::Matrix K, C;
  d.tangent(0.0, d.initial_position(), Eigen::Vector3d(1, 2, 3), K, C);
  CHECK(K.norm() == 0.0);
  CHECK(C.norm() == 0.0);
  const auto pw = d.power(0.0, d.initial_position(), Eigen::Vector3d(1, 2, 3));
  CHECK(pw.damping == 0.0);
  CHECK(pw.ground == 0.0);
}

TEST_CASE("bad parameters name the field") {
  auto p = deck(0.0);
  p.mass = -1.0;
  CHECK(error_of(p).find("mass") != std::string::npos);
  p = deck(0.0);
  p.friction = -0.1;
  CHECK(error_of(p).find("friction") != std::string::npos);
  p = deck(0.0);
  p.restitution = 1.5;
  CHECK(error_of(p).find("restitution") != std::string::npos);
  p = deck(0.0);
  p.deck.skew_deg = 85.0;
  CHECK(error_of(p).find("skew_deg") != std::string::npos);
  p = deck(0.0);
  p.deck.gap_left = -0.01;
  CHECK(error_of(p).find("gap_left") != std::string::npos);
  p = deck(0.0);
  p.inertia = std::nan("");
  CHECK(error_of(p).find("inertia") != std::string::npos);
}

TEST_CASE("an initial penetration is rejected, touching is allowed") {
  auto p = deck(0.0);
  p.initial_position = Eigen::Vector3d(0.021, 0, 0);  // right gap 0.02 m overrun
  const auto msg = error_of(p);
  CHECK(msg.find("initial penetration") != std::string::npos);
  CHECK(msg.find("contact 3") != std::string::npos);
  p.initial_position = Eigen::Vector3d(0.02, 0, 0);  // exactly touching
  CHECK(error_of(p).empty());
  // A rotation large enough to push corner 3 through the face: (W/2) sin(theta) moves it
  // towards +x when theta < 0; with gap 0.02 m, theta = -0.02 gives 1.22 * 0.02 = 0.024 m.
  p.initial_position = Eigen::Vector3d(0.0, 0, -0.02);
  CHECK(error_of(p).find("initial penetration") != std::string::npos);
}
