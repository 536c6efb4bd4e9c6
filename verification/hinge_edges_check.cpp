// Hinge contacts against end faces with edges (docs/bridge.md, "Contacts with edges"), checked
// against a two-body enumeration that shares no code with the model:
//  (a) the first contact of two free rigid decks with a relative rotation and a transverse
//      offset, approaching each other: the four corners of the two facing ends against the two
//      finite end faces, each gap g_N(t) = n_B(t) . (p_A(t) - a_B(t)) on the exact motion
//      (constant velocities: pose q0 + u0 t) bracketed on a fine grid and bisected to round-off,
//      a root counting only where the corner lies on the face (|g_T| <= (W/2) / cos alpha);
//      event-driven's first impact is at the earliest such root (1e-7 s);
//  (b) the impulse of that single-point impact in closed form (frictionless, Newton's law):
//      Lambda_N = -(1 + eps) m_eff gdot_N^-, m_eff = 1 / (1/m_A + 1/m_B + (r_A x n)^2 / I_A +
//      (r_B x n)^2 / I_B), against events.csv's impulse (1e-7 relative), and the velocities
//      after it, the linear and the angular momentum of the pair (conserved by the internal
//      impulse);
//  (c) the case the infinite face line got wrong: equal widths, the left deck turned by
//      0.02 rad about its centre, so that the right deck's corner strikes the line of the left
//      deck's end face beyond its edge, (L/2) theta^2 ahead of the real first contact, the left
//      deck's corner on the right deck's face;
//  (d) the redundant joint: equal widths, no relative rotation or offset, flush: the four
//      corner-against-face pairs coincide two by two (equal columns: a Delassus matrix of rank
//      2 for four contacts), and the model's two contacts of the joint are the right deck's
//      corners, with a regular 2 x 2 Delassus matrix;
//  (e) a narrow deck against a wide one: the narrow deck's corner strikes the wide face, and,
//      offset across, the wide deck's corner strikes the narrow face, as in (a)-(b).
#include "integrators/event_driven.hpp"
#include "integrators/recorder.hpp"
#include "models/deck_chain.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

namespace {

namespace ni = nsb::integrators;
namespace nm = nsb::models;
using Eigen::Vector2d;
using Eigen::Vector3d;

// Event-driven's impact time is its Brent bracket (event_time_tolerance 1e-13 s) on the exact
// free motion; the brief's bound, 1e-7 s, leaves six orders of margin.
constexpr double kTimeAgreement = 1e-7;  // [s]
// The impulse: the closed form against the impact LCP solved to 1e-12, times G's conditioning
// (~1e2 here); the bound asked for is 1e-7 relative.
constexpr double kImpulseAgreement = 1e-7;
// Momenta: the internal impulse changes them by round-off only (relative to sum m |v|).
constexpr double kRoundOff = 1e-12;

// One free deck of the pair: its plan and its exact motion, pose(t) = q0 + u0 t.
struct Deck {
  double mass = 0.0, inertia = 0.0, length = 0.0, width = 2.44;
  Vector3d q0 = Vector3d::Zero();  // world pose at t = 0 (x, y, theta)
  Vector3d u0 = Vector3d::Zero();  // (vx, vy, omega)
  Vector3d pose(double t) const { return q0 + u0 * t; }
};

struct Pair {
  double skew_deg = 0.0, restitution = 0.5;
  Deck left, right;
};

Vector2d rotate(double a, const Vector2d& v) {
  return {std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y()};
}
double cross(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// The facing ends, written out from the plan (docs/bridge.md, "Deck geometry"): the left deck's
// right end (+L/2 + y tan alpha, y), the right deck's left end (-L/2 + y tan alpha, y); corners
// at y = +-W/2, faces through (+-L/2, 0) with outward normals (+-cos alpha, -+sin alpha).
struct End {
  Vector2d corner[2];  // y = +W/2, -W/2 (body frame)
  Vector2d face_point, face_normal;
};
End end_of(const Pair& p, bool left_deck) {
  const double a = p.skew_deg * std::numbers::pi / 180.0;
  const double s = left_deck ? 1.0 : -1.0;
  const double l = left_deck ? p.left.length : p.right.length;
  const double h = 0.5 * (left_deck ? p.left.width : p.right.width);
  End e;
  e.corner[0] = {s * 0.5 * l + h * std::tan(a), h};
  e.corner[1] = {s * 0.5 * l - h * std::tan(a), -h};
  e.face_point = {s * 0.5 * l, 0.0};
  e.face_normal = {s * std::cos(a), -s * std::sin(a)};
  return e;
}

// A corner of deck A (side 0: +W/2, 1: -W/2) against the end face of deck B.
struct Candidate {
  bool a_is_left = false;
  int side = 0;
};

struct Contact {
  double t = std::numeric_limits<double>::infinity();
  Candidate which;
  Vector2d point = Vector2d::Zero(), normal = Vector2d::Zero();  // n out of B, towards A
};

// g_N and g_T of a candidate at time t on the exact motion.
Vector2d gaps(const Pair& p, const Candidate& c, double t, Contact* at = nullptr) {
  const Deck& a = c.a_is_left ? p.left : p.right;
  const Deck& b = c.a_is_left ? p.right : p.left;
  const End ea = end_of(p, c.a_is_left), eb = end_of(p, !c.a_is_left);
  const Vector3d qa = a.pose(t), qb = b.pose(t);
  const Vector2d corner = qa.head<2>() + rotate(qa.z(), ea.corner[c.side]);
  const Vector2d face = qb.head<2>() + rotate(qb.z(), eb.face_point);
  const Vector2d n = rotate(qb.z(), eb.face_normal);
  const Vector2d tangent(-n.y(), n.x());
  if (at != nullptr) {
    at->point = corner;
    at->normal = n;
  }
  return {n.dot(corner - face), tangent.dot(corner - face)};
}

// The earliest closing root of g_N in (0, t_end] on a grid of `steps`, bisected to round-off;
// with `bounded`, only a root where the corner lies on the face counts.
std::optional<double> first_root(const Pair& p, const Candidate& c, double t_end, bool bounded) {
  const Deck& b = c.a_is_left ? p.right : p.left;  // the deck whose face is struck
  const double half = 0.5 * b.width / std::cos(p.skew_deg * std::numbers::pi / 180.0);
  constexpr int kSteps = 20000;
  double t0 = 0.0, g0 = gaps(p, c, 0.0).x();
  for (int k = 1; k <= kSteps; ++k) {
    const double t1 = t_end * k / kSteps;
    const double g1 = gaps(p, c, t1).x();
    if (g0 > 0.0 && g1 <= 0.0) {
      double lo = t0, hi = t1;
      for (int it = 0; it < 200 && hi - lo > 0.0; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        (gaps(p, c, mid).x() > 0.0 ? lo : hi) = mid;
      }
      if (!bounded || std::abs(gaps(p, c, hi).y()) <= half) return hi;
    }
    t0 = t1;
    g0 = g1;
  }
  return std::nullopt;
}

// The enumeration: the earliest root over the four corner-against-face pairs.
Contact first_contact(const Pair& p, double t_end) {
  Contact best;
  for (bool a_left : {false, true}) {
    for (int side : {0, 1}) {
      const Candidate c{a_left, side};
      const auto t = first_root(p, c, t_end, true);
      if (t && *t < best.t) {
        best.t = *t;
        best.which = c;
      }
    }
  }
  if (std::isfinite(best.t)) gaps(p, best.which, best.t, &best);
  return best;
}

// The infinite-line model: the right deck's corners against the line of the left deck's face.
double first_contact_on_line(const Pair& p, double t_end) {
  double t = std::numeric_limits<double>::infinity();
  for (int side : {0, 1}) {
    const auto r = first_root(p, {false, side}, t_end, false);
    if (r) t = std::min(t, *r);
  }
  return t;
}

// Newton's law at one frictionless point contact between two free rigid bodies, closed form.
struct Impact {
  double impulse = 0.0;  // Lambda_N [kN s] on A along n (on B: -Lambda_N n)
  Vector3d u_left, u_right;
};
Impact closed_form_impact(const Pair& p, const Contact& c) {
  const Deck& a = c.which.a_is_left ? p.left : p.right;
  const Deck& b = c.which.a_is_left ? p.right : p.left;
  const Vector3d qa = a.pose(c.t), qb = b.pose(c.t);
  const Vector2d ra = c.point - qa.head<2>(), rb = c.point - qb.head<2>();
  const Vector2d& n = c.normal;
  auto point_velocity = [](const Vector3d& u, const Vector2d& r) {
    return Vector2d(u.x() - u.z() * r.y(), u.y() + u.z() * r.x());
  };
  const double gdot = n.dot(point_velocity(a.u0, ra) - point_velocity(b.u0, rb));
  const double m_eff = 1.0 / (1.0 / a.mass + 1.0 / b.mass +
                              std::pow(cross(ra, n), 2) / a.inertia +
                              std::pow(cross(rb, n), 2) / b.inertia);
  Impact out;
  out.impulse = -(1.0 + p.restitution) * m_eff * gdot;
  Vector3d ua = a.u0, ub = b.u0;
  ua.head<2>() += out.impulse * n / a.mass;
  ua.z() += cross(ra, n) * out.impulse / a.inertia;
  ub.head<2>() -= out.impulse * n / b.mass;
  ub.z() -= cross(rb, n) * out.impulse / b.inertia;
  out.u_left = c.which.a_is_left ? ua : ub;
  out.u_right = c.which.a_is_left ? ub : ua;
  return out;
}

// The pair as a deck chain (models/deck_chain.hpp) whose abutments are 1 m away (far): the
// hinge's contacts are 2 (+W/2) and 3 (-W/2), frictionless with the pair's restitution.
nm::DeckChain::Parameters chain(const Pair& p) {
  nm::DeckChain::Parameters c;
  c.width = p.left.width;
  c.skew_deg = p.skew_deg;
  c.decks = {{.mass = p.left.mass, .inertia = p.left.inertia, .length = p.left.length,
              .width = p.left.width},
             {.mass = p.right.mass, .inertia = p.right.inertia, .length = p.right.length,
              .width = p.right.width}};
  const double gap = p.right.q0.x() - 0.5 * p.right.length - (p.left.q0.x() + 0.5 * p.left.length);
  c.joints = {{.gap = 1.0}, {.gap = gap, .restitution = p.restitution}, {.gap = 1.0}};
  const Deck* decks[2] = {&p.left, &p.right};
  for (int i = 0; i < 2; ++i) {
    const Vector3d rest(nm::DeckChain::rest_position(c, i), 0.0, 0.0);
    c.decks[static_cast<std::size_t>(i)].initial_displacement = decks[i]->q0 - rest;
    c.decks[static_cast<std::size_t>(i)].initial_velocity = decks[i]->u0;
  }
  return c;
}

struct Run {
  ni::Event impact;          // the first impact
  int impacts = 0;
  Vector3d u_left, u_right;  // at the end
  Vector3d q_left, q_right;  // world poses at the end
};

Run run_event_driven(const Pair& p, double end_time) {
  const nm::DeckChain::Parameters c = chain(p);
  nm::Assembly a(nm::DeckChain::parts(c));
  ni::OutputGroups groups;
  groups.add(ni::OutputGroup::kImpulses);
  ni::Recorder rec(a, 0.0, groups);
  ni::EventDrivenOptions o;
  o.end_time = end_time;
  const ni::RunResult r = ni::event_driven(a, o, rec);
  REQUIRE(r.completed);
  Run out;
  for (const auto& e : rec.events()) {
    if (e.kind != ni::EventKind::kImpact) continue;
    if (out.impacts++ == 0) out.impact = e;
  }
  const std::size_t last = rec.rows() - 1;
  Eigen::VectorXd q(6), u(6);
  int k = 0;
  for (const auto& name : a.coordinate_names()) q(k++) = rec.at(last, rec.column(name));
  k = 0;
  for (const auto& name : a.velocity_names()) u(k++) = rec.at(last, rec.column(name));
  out.q_left = q.head<3>();  // the history's coordinates are the world poses
  out.q_right = q.tail<3>();
  out.u_left = u.head<3>();
  out.u_right = u.tail<3>();
  return out;
}

// Linear momentum and angular momentum about the origin of the pair.
Vector3d momenta(const Pair& p, const Vector3d& ql, const Vector3d& ul, const Vector3d& qr,
                 const Vector3d& ur) {
  auto of = [](const Deck& d, const Vector3d& q, const Vector3d& u) {
    return Vector3d(d.mass * u.x(), d.mass * u.y(),
                    d.inertia * u.z() + d.mass * (q.x() * u.y() - q.y() * u.x()));
  };
  return of(p.left, ql, ul) + of(p.right, qr, ur);
}

// Left deck at rest where the chain puts it (its left end 1 m from the left abutment), turned
// by theta_l; right deck turned by theta_r, offset by e across the axis, `gap` along it,
// closing at speed v (and turning at omega).
Pair make_pair(double skew, double theta_l, double theta_r, double e, double gap, double v,
               double omega) {
  Pair p;
  p.skew_deg = skew;
  p.left = {.mass = 70.0, .inertia = 1640.0, .length = 16.75,
            .q0 = Vector3d(1.0 + 0.5 * 16.75, 0.0, theta_l), .u0 = Vector3d::Zero()};
  p.right = {.mass = 95.0, .inertia = 3100.0, .length = 20.5,
             .q0 = Vector3d(1.0 + 16.75 + gap + 0.5 * 20.5, e, theta_r),
             .u0 = Vector3d(-v, 0.0, omega)};
  return p;
}

void check_against_enumeration(const Pair& p, double t_end, Candidate expected) {
  const Contact c = first_contact(p, t_end);
  REQUIRE(std::isfinite(c.t));
  CHECK(c.which.a_is_left == expected.a_is_left);
  CHECK(c.which.side == expected.side);
  const Impact oracle = closed_form_impact(p, c);
  const Run r = run_event_driven(p, c.t + 1e-4);
  REQUIRE(r.impacts == 1);
  MESSAGE("first impact: enumeration t = ", c.t, " s, event-driven t = ", r.impact.t,
          " s; impulse ", oracle.impulse, " kN s against ", r.impact.impulse_normal);
  CHECK(std::abs(r.impact.t - c.t) <= kTimeAgreement);
  CHECK(r.impact.contact == 3 + c.which.side);  // the hinge's contact of that side, 1-based
  CHECK(std::abs(r.impact.impulse_normal - oracle.impulse) <=
        kImpulseAgreement * std::abs(oracle.impulse));
  const double vscale = p.left.u0.norm() + p.right.u0.norm();
  CHECK((r.u_left - oracle.u_left).cwiseAbs().maxCoeff() <= kImpulseAgreement * vscale);
  CHECK((r.u_right - oracle.u_right).cwiseAbs().maxCoeff() <= kImpulseAgreement * vscale);
  // Momenta before (t = 0) and at the end, from the run's own end state.
  const Vector3d before = momenta(p, p.left.q0, p.left.u0, p.right.q0, p.right.u0);
  const Vector3d after = momenta(p, r.q_left, r.u_left, r.q_right, r.u_right);
  const double pscale = p.left.mass * p.left.u0.norm() + p.right.mass * p.right.u0.norm();
  CHECK(std::abs(after.x() - before.x()) <= kRoundOff * pscale);
  CHECK(std::abs(after.y() - before.y()) <= kRoundOff * pscale);
  // Angular momentum about the origin: positions ~10 m, so ~10 pscale of round-off scale.
  CHECK(std::abs(after.z() - before.z()) <= kRoundOff * 100.0 * pscale);
}

}  // namespace

TEST_CASE("hinge edges: rotation and offset, first impact and impulse as the enumeration") {
  SUBCASE("the right deck's corner on the left deck's face") {
    // Right deck turned by +0.01 rad (its left end moves by -(L/2) 0.01 = -0.1025 m across),
    // offset by -0.05 m and turning at 0.02 rad/s: its +W/2 corner leads and lies on the face.
    check_against_enumeration(make_pair(0.0, 0.0, 0.01, -0.05, 0.05, 0.5, 0.02), 0.5,
                              {.a_is_left = false, .side = 0});
  }
  SUBCASE("the left deck's corner on the right deck's face, skew") {
    // 15 deg skew, right deck turned by -0.015 rad and offset by -0.4 m: the left deck's
    // -W/2 corner is the first on a face (the right deck's -W/2 corner is beyond the edge).
    const Pair p = make_pair(15.0, 0.0, -0.015, -0.4, 0.08, 0.6, 0.0);
    check_against_enumeration(p, 0.5, first_contact(p, 0.5).which);
    CHECK(first_contact(p, 0.5).which.a_is_left);
  }
}

TEST_CASE("hinge edges: a corner beyond the other deck's edge strikes no face") {
  // Equal widths, the left deck turned by -0.02 rad about its centre: its right end moves by
  // -(L/2) 0.02 = -0.1675 m across and its +W/2 corner leads. The right deck's +W/2 corner,
  // 0.1675 m beyond that corner, meets the line of the left face (L/2) theta^2 = 3.35e-3 m
  // early: at 1.6 m/s, 2.1 ms before the left deck's corner meets the right deck's face.
  Pair p = make_pair(0.0, -0.02, 0.0, 0.0, 0.05, 1.6, 0.0);
  p.right.length = p.left.length;
  p.right.q0.x() = p.left.q0.x() + p.left.length + 0.05;
  const Contact c = first_contact(p, 0.2);
  const double on_line = first_contact_on_line(p, 0.2);
  MESSAGE("infinite line: ", on_line, " s; finite faces: ", c.t, " s; early by ",
          (c.t - on_line) * 1e3, " ms");
  // (L/2) theta^2 / v to first order; the exact difference to 2 %.
  CHECK(c.t - on_line == doctest::Approx(0.5 * 16.75 * 0.02 * 0.02 / 1.6).epsilon(0.02));
  CHECK(c.which.a_is_left);
  check_against_enumeration(p, 0.2, {.a_is_left = true, .side = 0});
}

TEST_CASE("hinge edges: coincident corners make one contact per side, not two") {
  // Equal widths, flush (gap 0), no rotation or offset: corner 0 of the right deck and corner
  // 2 of the left deck are the same point, and so for corners 1 and 3.
  const Pair p = make_pair(20.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0);
  const nm::DeckChain::Parameters c = chain(p);
  nm::Assembly a(nm::DeckChain::parts(c));
  std::vector<ni::ContactData> data;
  a.contact_data(0.0, a.initial_position(), a.initial_velocity(), data);
  const Eigen::VectorXd minv = a.mass().diagonal().cwiseInverse();
  // The four pairs' normal columns, by hand: corner of A at p on the face of B (normal n out
  // of B): A gets (n, r_A x n), B gets (-n, -r_B x n).
  Eigen::MatrixXd w4 = Eigen::MatrixXd::Zero(6, 4);
  int col = 0;
  for (bool a_left : {false, true}) {
    for (int side : {0, 1}) {
      Contact k;
      gaps(p, {a_left, side}, 0.0, &k);
      const Deck& da = a_left ? p.left : p.right;
      const Deck& db = a_left ? p.right : p.left;
      const int oa = a_left ? 0 : 3, ob = a_left ? 3 : 0;
      const Vector2d ra = k.point - da.q0.head<2>(), rb = k.point - db.q0.head<2>();
      w4.block<2, 1>(oa, col) = k.normal;
      w4(oa + 2, col) = cross(ra, k.normal);
      w4.block<2, 1>(ob, col) = -k.normal;
      w4(ob + 2, col) = -cross(rb, k.normal);
      ++col;
    }
  }
  // The coincidence: the left deck's corner on the right face has the right deck's column.
  CHECK((w4.col(0) - w4.col(2)).norm() <= 1e-12 * w4.col(0).norm());
  CHECK((w4.col(1) - w4.col(3)).norm() <= 1e-12 * w4.col(1).norm());
  const Eigen::MatrixXd g4 = w4.transpose() * minv.asDiagonal() * w4;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> e4(g4);
  CHECK(e4.eigenvalues()(1) <= 1e-12 * e4.eigenvalues()(3));  // rank 2: singular
  // The model: two contacts at the joint, both candidates, the right deck's corners' columns.
  Eigen::MatrixXd w2(6, 2);
  for (int s = 0; s < 2; ++s) {
    const auto& d = data[static_cast<std::size_t>(2 + s)];
    CHECK_FALSE(d.far);
    CHECK(std::abs(d.gap_normal) <= 1e-12);
    CHECK((d.w_normal - w4.col(s)).norm() <= 1e-12 * w4.col(s).norm());
    w2.col(s) = d.w_normal;
  }
  const Eigen::MatrixXd g2 = w2.transpose() * minv.asDiagonal() * w2;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> e2(g2);
  CHECK(e2.eigenvalues()(0) >= 1e-3 * e2.eigenvalues()(1));  // regular
}

TEST_CASE("hinge edges: a narrow deck against a wide one, first impact and impulse as the "
          "enumeration") {
  SUBCASE("the narrow deck's corner on the wide deck's face") {
    // Left deck 4.0 m wide, right deck 2.44 m, offset by +0.5 m and turned by +0.01 rad: its
    // +W/2 corner leads (it moves by -(W/2) 0.01 along the axis) at y = 0.5 + 1.22 - (L/2) 0.01
    // = 1.6175 m, on the wide face (|y| <= 2.0). The wide deck's corners, at y = -+2.0, lie
    // beyond the narrow face (from -0.8225 to 1.6175 m): the side's contact is the narrow
    // deck's corner.
    Pair p = make_pair(0.0, 0.0, 0.01, 0.5, 0.05, 0.5, 0.0);
    p.left.width = 4.0;
    check_against_enumeration(p, 0.5, {.a_is_left = false, .side = 0});
  }
  SUBCASE("offset across, the wide deck's corner on the narrow deck's face, skew") {
    // 10 deg skew, left deck 4.0 m wide turned by +0.01 rad (its -W/2 corner at the right end
    // leads), right deck 2.44 m offset by -2.5 m: its face runs from y = -3.72 to -1.28 m, so
    // the wide deck's -W/2 corner (y = -2.0) lies on it, while the narrow deck's -W/2 corner
    // (y = -3.72) lies beyond the wide face's end at -2.0. Its +W/2 corner (y = -1.28) lies
    // on the wide face but trails. The faces are parallel lines at rest, 2.5 m apart across
    // the axis, so 2.5 tan(10 deg) = 0.44 m further apart than the 0.05 m gap along it: the
    // first contact comes after ~1 s at 0.5 m/s.
    Pair p = make_pair(10.0, 0.01, 0.0, -2.5, 0.05, 0.5, 0.0);
    p.left.width = 4.0;
    check_against_enumeration(p, 1.5, {.a_is_left = true, .side = 1});
  }
}
