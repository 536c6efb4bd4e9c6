// The parts a bridge is assembled from (DESIGN.md, "Models are assemblies of parts"): rigid
// bodies, prescribed bodies, connectors between a body and the ground, and unilateral
// frictional contacts of a body corner against a face of the ground, of a prescribed body or of
// another body. models/assembly.hpp sums them into one integrators::System.
//
// Rigid body b has the generalized coordinates q_b = (x, y, theta) of its centre and the
// velocities u_b = (vx, vy, omega); its plan is the parallelogram of models/deck_geometry.hpp
// (length L along the body axis, width W, skew alpha; corners 0..3 numbered as there).
// A prescribed body (an abutment seat, or the fixed ground) moves with the support excitation:
// its pose is (reference point + (u_x(t), u_y(t)), phi(t)) (eq. 2 of Shi & Dimitrakopoulos
// 2017, multi-support excitation).
//
// Units: kN, t, m, s, rad.
#pragma once

#include "integrators/system.hpp"
#include "models/connectors.hpp"
#include "models/contact_geometry.hpp"
#include "models/ground_motion.hpp"
#include "models/takeda.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace nsb::models {

// A contact is reported `far` when g_N > kFarGap + kFarHorizon * max(0, -gdot_N): it cannot
// close within kFarHorizon unless its closing speed grows by more than kFarGap / kFarHorizon
// = 1 m/s, which neither the free deck (no forces) nor the bridge (bent forces of a few
// hundred kN on 140 t give < 5 m/s^2, i.e. < 0.5 m/s within 0.1 s) can do between two
// contact evaluations of any step up to 0.1 s.
inline constexpr double kFarGap = 0.1;      // [m]
inline constexpr double kFarHorizon = 0.1;  // [s]

// Initial gaps below -kPenetrationTolerance are rejected as an initial penetration; the
// tolerance absorbs round-off of the corner coordinates (1e-12 of a 30 m deck is ~1e-11 m).
inline constexpr double kPenetrationTolerance = 1e-9;  // [m]

}  // namespace nsb::models

namespace nsb::models::parts {

// Ground motion of one support component; null means none.
using Motion = std::shared_ptr<const GroundMotion>;

// A free rigid body in the plane (a deck segment).
struct RigidBody {
  double mass = 0.0;       // m [t], > 0
  double inertia = 0.0;    // I about the centre [t m^2], > 0
  double length = 0.0;     // L along the body axis [m], > 0
  double width = 0.0;      // W across it [m], > 0
  double skew_deg = 0.0;   // alpha of both end faces [deg], |alpha| < 80
  // Each end face its own angle, and a curved plan (models/deck_geometry.hpp: the same
  // fields): the left (right) end's skew, none: skew_deg; R of a curved body's centreline,
  // 0: straight (length is then the arc length).
  std::optional<double> skew_left_deg{};
  std::optional<double> skew_right_deg{};
  double radius = 0.0;
  Eigen::Vector3d initial_position = Eigen::Vector3d::Zero();  // (x, y, theta) [m, m, rad]
  Eigen::Vector3d initial_velocity = Eigen::Vector3d::Zero();  // (vx, vy, omega)
  // The rest pose the coordinates are measured from: the body's pose is rest + q, so that q
  // is the displacement from the rest layout of several bodies (a bridge in segments). The
  // contacts see the pose; the bents act on q (their springs are unstretched at q = 0).
  // Zero: q is the pose itself (a bridge of one deck, whose rest centre is the origin).
  Eigen::Vector3d rest = Eigen::Vector3d::Zero();  // [m, m, rad]
  // Throws std::invalid_argument naming the field, prefixed with `prefix`.
  void validate(const std::string& prefix) const;
  // Corner 0..3 in the body frame (models/deck_geometry.hpp numbering) [m].
  Eigen::Vector2d corner(int index) const;
};

// The two end faces of a rigid body.
enum class End { kLeft, kRight };
// A face of a body or of a prescribed body, in that body's frame: a point on it and its unit
// normal, pointing out of the body (towards whatever touches the face). The face extends
// half_length either way from `point` along its tangent t = R(+90 deg) n; infinity is a line
// (the abutment seats, wider than the deck).
struct Face {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();   // [m]
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX(); // unit length
  double half_length = std::numeric_limits<double>::infinity();  // [m], > 0
};
// The end face of `body`: through its end point on the axis (+-L/2, 0 from the axis's
// midpoint; models/deck_geometry.hpp), normal (-+cos alpha, +-sin alpha) outwards, alpha that
// end's angle; taken as a line (a backwall seat, wider than the deck that strikes it).
Face end_face(const RigidBody& body, End end);
// The same face between the end's two corners, half_length their distance from the end point
// ((W/2) / cos alpha of a straight end, W/2 of a curved deck's radial end; a hinge).
Face bounded_end_face(const RigidBody& body, End end);

// A body whose motion is prescribed: the pose of its frame at time t is
// (reference.x + u_x(t), reference.y + u_y(t), phi(t)); null motions are zero.
struct PrescribedBody {
  Eigen::Vector2d reference = Eigen::Vector2d::Zero();  // frame origin at rest [m]
  Motion longitudinal;  // u_x(t) along global x [m]
  Motion transverse;    // u_y(t) along global y [m]
  Motion rotation;      // phi(t) about the frame origin; the record's "acceleration" is the
                        // angular acceleration [rad/s^2]
};

// A bent between a body and the ground: two Takeda springs (models/takeda.hpp) at the position
// s along the body axis, acting on the displacement of that point from rest (q = (x, y,
// theta), RigidBody::rest) relative to the bent's own support motion (small rotations; the
// bent kinematics are linear in theta, |theta| < 0.01 rad in the benchmark):
//   F_x = Takeda_x(x - u_gx(t)),   F_y = Takeda_y(y + s theta - u_gy(t)),
//   f_b -= F_x (1, 0, 0) + F_y (0, 1, s).
// A bent with columns (column_offsets not empty) or its own skew beta is n columns, each with
// 1/n of both springs (k0, cracking and yield forces; the yield displacement is the bent's),
// at the point r_c = (s + e_c tan beta, e_c) of the body frame, on the bent's line through
// (s, 0) at beta from the transverse axis (the deck faces' convention, docs/bridge.md). The
// longitudinal spring acts along the line's normal n = (cos beta, -sin beta), the transverse
// one along the line t = (sin beta, cos beta): for a direction a, the column's deformation is
//   delta_a = a . (p_c - u_g(t)),  p_c = (x - r_c,y theta, y + r_c,x theta),
//   so d delta_a / d q = J_a = (a_x, a_y, a_y r_c,x - a_x r_c,y),   f_b -= F_a J_a,
// which with no offsets and beta = 0 is the single spring pair above (docs/bridge.md, "Bents
// with their columns").
struct Bent {
  int body = 0;                    // index of the rigid body, >= 0
  double position = 0.0;           // s from the body centre along its axis [m], |s| <= L/2
  takeda::Parameters longitudinal; // spring along x (all columns together)
  takeda::Parameters transverse;   // spring along y
  Motion ground_longitudinal;      // u_gx(t); null: fixed
  Motion ground_transverse;        // u_gy(t); null: fixed
  std::vector<double> column_offsets{};  // e_c, the columns' transverse positions [m];
                                         //   empty: the bent acts at (s, 0)
  double skew_deg = 0.0;                 // beta [deg], |beta| < 80
};

// What a corner touches: the face of a prescribed body, or the face of another rigid body.
enum class Obstacle { kPrescribed, kBody };

// A restrainer cable (models/connectors.hpp, Cable) from the anchor point of a rigid body to
// the anchor point of another body (across a hinge) or of a prescribed body (an abutment
// seat). Anchors are in each body's frame; the rest length L0 is their distance in the rest
// layout (q = 0, seats at their reference, t-independent) and the elongation is |p_a - p_b| -
// L0 with the exact positions. The tension F pulls the anchors together: body a gets
// -F (e, r_a x e), body b +F (e, r_b x e), e = (p_a - p_b) / |p_a - p_b|, r the anchor from
// the body centre in the global frame.
struct Restrainer {
  int body = 0;                                       // body of anchor a, >= 0
  Eigen::Vector2d anchor = Eigen::Vector2d::Zero();   // in body's frame [m]
  Obstacle other = Obstacle::kPrescribed;             // what anchor b is on
  int other_index = 0;                                // index among bodies or prescribed
  Eigen::Vector2d other_anchor = Eigen::Vector2d::Zero();  // in the other's frame [m]
  connectors::CableParameters cable;
};

// A connector between a body point at position s along its axis and the ground (an
// elastomeric bearing, a backfill, a pile or tie spring): one uniaxial law per direction
// (models/connectors.hpp, Law) acting on the point's displacement relative to its own
// support motion, as a bent (small rotations):
//   F_x = law_x(x - u_gx(t)),   F_y = law_y(y + s theta - u_gy(t)),
//   f_b -= F_x (1, 0, 0) + F_y (0, 1, s).
struct GroundLink {
  int body = 0;                  // >= 0
  double position = 0.0;         // s from the body centre along its axis [m], |s| <= L/2
  connectors::LawParameters longitudinal;
  connectors::LawParameters transverse;
  Motion ground_longitudinal;    // u_gx(t); null: fixed
  Motion ground_transverse;      // u_gy(t); null: fixed
};

// Rayleigh damping C = a0 M + a1 K0 on the assembled mass and initial stiffness, from two
// modal ratios (models/rayleigh.hpp), acting on the velocity relative to the quasi-static
// motion of the supports: f_D = -C (u - us_dot(t)) (Chopra, Dynamics of Structures, sec. 9.7).
struct RayleighParts {
  double ratio_i = 0.0, ratio_j = 0.0;  // zeta of modes i and j, in [0, 1)
  int mode_i = 1, mode_j = 3;           // 1-based modes of (M, K0), distinct
};

// A unilateral frictional contact: corner `corner` of rigid body `body` against `face` of the
// obstacle (index `obstacle_index` among the prescribed or the rigid bodies). A corner touches
// only the face that exists: against a face of finite half_length the contact is far (no
// candidate) while the corner's projection g_T lies beyond the face's end, |g_T| > half_length.
//
// One side of a joint between two bodies (docs/bridge.md, "Contacts with edges"): with
// partner_corner >= 0 the contact is the pair of corner-against-face contacts of that side,
// this corner against the obstacle's `face` and the obstacle's corner `partner_corner`
// against this body's `partner_face`. Of the two, the contact is the one whose corner lies
// further inside the other's face (parts::joint_side), the first on a tie: with equal widths
// and no relative offset the two corners coincide and so do their columns, and the side is
// one contact, not two equal ones (a Delassus matrix without repeated columns).
struct CornerContact {
  int body = 0;                 // the body whose corner touches, >= 0
  int corner = 0;               // 0..3 (models/deck_geometry.hpp numbering)
  Obstacle obstacle = Obstacle::kPrescribed;
  int obstacle_index = 0;       // >= 0, a different body when obstacle == kBody
  Face face;                    // in the obstacle's frame
  double restitution = 0.0;     // Newton's eps_N in [0, 1]
  double friction = 0.0;        // Coulomb's mu >= 0
  double stiffness = 0.0;       // compliance Hertz k [kN/m^1.5], >= 0; 0: the scaled default
  // What the contact is, for the outputs (summary.json "contacts", docs/outputs.md):
  // family "abutment", "hinge" or "shear_key" (empty: not a bridge part) and a name within
  // it, e.g. "left +W/2", "hinge 1 -W/2", "shear_key_right_plus". No physics reads them.
  std::string family;
  std::string name;
  int partner_corner = -1;      // the obstacle's corner 0..3 of the same side (kBody); -1: none
  Face partner_face{};          // the face of `body` it touches, in the body's frame
};

// A shear key (models/shear_keys.hpp): contact `contact` (0-based, among the assembly's
// contacts) is a key that breaks when the mean contact force of an accepted step, normal
// impulse / h, exceeds `capacity`; from then on the contact is far for good.
struct ShearKey {
  int contact = 0;          // >= 0, the key's contact
  std::string name;         // the limit state's name, e.g. "shear_key_left_plus"
  double capacity = 0.0;    // [kN], >= 0; 0: unbreakable
};

// Kinematics of a corner of body A against a face of body B (both free). corner_contact()
// (models/contact_geometry.hpp) with B as an obstacle moving at u_B gives g_N, g_T, the columns
// of A and the relative rates; its rheonomic terms are the part of the rates linear in u_B,
// which here belong to B's columns. The contact impulse acts on B at the contact point p
// with the opposite sign (Newton's third law), so with d = p - (x_B, y_B):
//   W_N,B = (-n_x, -n_y, -d x n),   W_T,B = (-t_x, -t_y, -d x t),   what_N = what_T = 0,
// equal to the u_B-coefficients of what_N = Phidot (g_T - r_a x n) - n . v_B (d = r_a + g_N n
// + g_T t, t x n = -1). wbar: corner_contact()'s with B's acceleration set to zero, since
// the part linear in B's acceleration is W_B^T udot_B.
struct BodyContactKinematics {
  ContactKinematics a;                                 // as corner_contact(), for body A
  Eigen::Vector3d w_normal_b = Eigen::Vector3d::Zero();   // W_N,B [-, -, m]
  Eigen::Vector3d w_tangent_b = Eigen::Vector3d::Zero();  // W_T,B [-, -, m]
};
BodyContactKinematics corner_on_body(const CornerFace& c, const Eigen::Vector3d& q_a,
                                     const Eigen::Vector3d& u_a, const Eigen::Vector3d& q_b,
                                     const Eigen::Vector3d& u_b);
// Its normal part, the same numbers: corner_contact_normal() with B as the obstacle, and W_N,B.
struct BodyContactNormal {
  ContactNormal a;                                      // as corner_contact_normal(), for A
  Eigen::Vector3d w_normal_b = Eigen::Vector3d::Zero();   // W_N,B [-, -, m]
};
BodyContactNormal corner_on_body_normal(const CornerFace& c, const Eigen::Vector3d& q_a,
                                        const Eigen::Vector3d& u_a, const Eigen::Vector3d& q_b,
                                        const Eigen::Vector3d& u_b);

// Writes the contact data of body A's corner (its columns at offset_a) and, when w_*_b are
// given, of body B (at offset_b) into `out`, whose vectors are sized dofs(): the other entries
// are zeroed. `far` as kFarGap and kFarHorizon say (above). write_contact takes
// what_N, what_T from `k` (a prescribed obstacle); write_body_contact sets them to zero.
// write_contact and write_contact_normal run for every contact at every step: inline, so
// that a one-body system's columns (offset 0, size 3) are plain copies.
inline void write_contact(const ContactKinematics& k, int offset_a, double restitution,
                          double friction, integrators::ContactData& out);
void write_body_contact(const BodyContactKinematics& k, int offset_a, int offset_b,
                        double restitution, double friction, integrators::ContactData& out);
// The normal fields only (System::contact_normals): gap_normal, w_normal, what_normal, far,
// as write_contact writes them; the other fields of `out` keep their values.
inline void write_contact_normal(const ContactNormal& k, int offset_a,
                                 integrators::ContactData& out);
void write_body_contact_normal(const BodyContactKinematics& k, int offset_a, int offset_b,
                               integrators::ContactData& out);
void write_body_contact_normal(const BodyContactNormal& k, int offset_a, int offset_b,
                               integrators::ContactData& out);

// `far`: the contact cannot close within kFarHorizon (models/parts.hpp, kFarGap).
inline bool is_far(double gap_normal, double gap_rate_normal) {
  return gap_normal > kFarGap + kFarHorizon * std::max(0.0, -gap_rate_normal);
}

// Two corners of one side of a joint closer than this across the faces count as coincident
// (equal widths, no relative offset): the side keeps its first pair, so that a joint at rest
// gives the same contact whatever the round-off of its corners (1e-9 m is the tolerance of
// an initial penetration, far above the round-off ~1e-13 m of a 30 m body's corners).
inline constexpr double kEdgeTie = kPenetrationTolerance;  // [m]

// A corner's distance beyond the end of a face, |g_T| - half_length (< 0: on the face) [m].
inline double beyond_edge(double gap_tangent, double half_length) {
  return std::abs(gap_tangent) - half_length;
}

// Which pair of a joint's side is its contact, and whether it is a candidate
// (docs/bridge.md, "Contacts with edges"). first_beyond, second_beyond: beyond_edge() of the
// side's first pair (this body's corner on the obstacle's face) and of its second (the
// obstacle's corner on this body's face). The innermost corner is the one that bounds the
// faces' overlap on this side, so it is the contact; it lies on the other face whenever the
// joint is closed, and beyond it by at most g_N sin(theta) (theta the faces' relative angle)
// while the joint is open, so the side stays a candidate while beyond <= max(kEdgeTie, g_N).
// The floor kEdgeTie is for a flush joint: its coincident corners lie at the faces' ends up
// to round-off (beyond ~ +-1e-16 m with g_N ~ -1e-16 m), which must not make the side far.
struct JointSide {
  bool second = false;     // the second pair is the contact
  bool candidate = true;   // false: no overlap of the faces on this side, the contact is far
};
inline JointSide joint_side(double first_beyond, double second_beyond, double first_gap,
                            double second_gap) {
  JointSide s;
  s.second = second_beyond < first_beyond - kEdgeTie;
  const double beyond = s.second ? second_beyond : first_beyond;
  const double gap = s.second ? second_gap : first_gap;
  s.candidate = beyond <= std::max(kEdgeTie, gap);
  return s;
}

inline void write_contact(const ContactKinematics& k, int offset_a, double restitution,
                          double friction, integrators::ContactData& out) {
  // A column of a 3-DOF system is the body's alone; a longer one is zero outside the body.
  out.gap_normal = k.gap_normal;
  if (out.w_normal.size() != 3) out.w_normal.setZero();
  if (out.w_tangent.size() != 3) out.w_tangent.setZero();
  out.w_normal.segment<3>(offset_a) = k.w_normal;
  out.w_tangent.segment<3>(offset_a) = k.w_tangent;
  out.what_normal = k.what_normal;
  out.what_tangent = k.what_tangent;
  out.wbar_normal = k.wbar_normal;
  out.wbar_tangent = k.wbar_tangent;
  out.restitution = restitution;
  out.friction = friction;
  out.far = is_far(k.gap_normal, k.gap_rate_normal);
}

inline void write_contact_normal(const ContactNormal& k, int offset_a,
                                 integrators::ContactData& out) {
  out.gap_normal = k.gap_normal;
  if (out.w_normal.size() != 3) out.w_normal.setZero();
  out.w_normal.segment<3>(offset_a) = k.w_normal;
  out.what_normal = k.what_normal;
  out.far = is_far(k.gap_normal, k.gap_rate_normal);
}

// The distinct ground motions of an assembly, each evaluated once per distinct time t (an
// integrator asks for forces, contacts and power at the same t several times per step, and
// supports often share one record). The values are a cache inside const calls: one table must
// not be used from several threads at once.
class MotionTable {
 public:
  static constexpr int kNone = -1;  // index of "no motion": displacement etc. are 0
  struct Value {
    double d = 0.0, v = 0.0, a = 0.0;  // displacement, velocity, acceleration
  };
  // Index of m (supports sharing a GroundMotion object share an entry); kNone for null.
  // needs_acceleration: the acceleration is evaluated (contact kinematics of a seat need it,
  // springs do not).
  int add(const Motion& m, bool needs_acceleration);
  // Evaluates every motion at t unless the values are already at t; true if it evaluated.
  bool update(double t) const {
    if (t == t_) return false;
    evaluate(t);
    return true;
  }
  std::size_t size() const { return motions_.size(); }
  // Forgets the values, so that the next update evaluates (after the motions were replaced).
  void invalidate() { t_ = std::numeric_limits<double>::quiet_NaN(); }
  const Value& value(int index) const {
    static constexpr Value kZero{};
    return index == kNone ? kZero : values_[static_cast<std::size_t>(index)];
  }

 private:
  void evaluate(double t) const {
    for (std::size_t i = 0; i < motions_.size(); ++i) {
      const GroundMotion::Values g = motions_[i]->values(t);
      Value& v = values_[i];
      v.d = g.displacement;
      v.v = g.velocity;
      v.a = needs_acceleration_[i] ? g.acceleration : 0.0;
    }
    t_ = t;
  }

  std::vector<Motion> motions_;
  std::vector<char> needs_acceleration_;
  mutable std::vector<Value> values_;
  mutable double t_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace nsb::models::parts
