// A mechanical system assembled from parts (models/parts.hpp): the one integrators::System
// that the contact stage and the integrators see, summing what each part adds.
//
// Equation of motion (eq. 2 of Shi & Dimitrakopoulos 2017, for any number of bodies):
//   M udot = f_S + f_D + W_N lambda_N + W_T lambda_T,   M = diag(m_b, m_b, I_b) per body,
//   f_S = sum over bents of their Takeda forces (models/parts.hpp, Bent),
//   f_D = -C (u - us_dot(t)),   C = a0 M + a1 K0 (RayleighParts; none without it),
// where K0 is the initial stiffness of the bents and us = K0^-1 sum_j k0_j b_j u_g,j the
// quasi-static displacement of the supports (Chopra, Dynamics of Structures, sec. 9.7).
// Bents join a body to the ground, so K0 and C are block-diagonal, one 3x3 block per body,
// and us is found body by body. The contacts are listed in the order given; each is a corner
// against a prescribed face (rheonomic, models/contact_geometry.hpp) or against a face of
// another body (W_N and W_T span both bodies' DOFs, parts::corner_on_body). A body's
// coordinates are its displacement from its rest pose (parts::RigidBody::rest): contacts see
// rest + q, bents and damping q.
//
// Cost: every evaluation is a pass over vectors of concrete part types sized at
// construction; no allocation and no virtual call per part. Ground motions are evaluated once
// per distinct t (parts::MotionTable, a cache inside const calls), the seats' poses once per
// distinct t at which contacts or connectors ask for them: one Assembly must not be used from
// several threads at once. An assembly of one body (the bridge of one deck, the free deck)
// runs the per-step evaluations compiled for it, chosen at construction: its coordinates are
// the first three, its contact columns have three rows and every contact is against a
// prescribed face. The numbers are the general form's, operation for operation.
//
// A copy is an independent system in the same state (the bents' committed and trial Takeda
// states, the connectors', the keys' peaks and breaks, the limit watch; the ground motions,
// immutable, are shared): the system's half of a saved state from which a run restarts
// (integrators::MoreauJeanCheckpoint holds the integrator's half).
//
// A bridge of one deck (models/bridge_parts.hpp) is one body, two prescribed seats, its bents
// and four contacts; a free deck is one body without bents or damping against two fixed seats.
//
// Units: kN, t, m, s, rad.
#pragma once

#include "integrators/system.hpp"
#include "models/connector_set.hpp"
#include "models/contact_geometry.hpp"
#include "models/limit_watch.hpp"
#include "models/parts.hpp"
#include "models/rayleigh.hpp"
#include "models/takeda.hpp"

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace nsb::models {

class Assembly final : public integrators::SystemBase {
 public:
  struct Parts {
    std::vector<parts::RigidBody> bodies;          // >= 1; DOFs 3b .. 3b + 2 of body b
    std::vector<parts::PrescribedBody> prescribed; // seats and fixed ground faces
    std::vector<parts::Bent> bents;
    std::vector<parts::CornerContact> contacts;    // output order (gN1, gN2, ...)
    std::optional<parts::RayleighParts> damping;   // needs a bent on every body (K0 > 0)
    std::vector<parts::ShearKey> shear_keys;       // breakable contacts (models/shear_keys.hpp)
    LimitSpec limits;                              // the limit states watched (none: empty)
    // Connectors (models/connector_set.hpp): restrainer cables, and links to the ground
    // (bearings, backfills) whose initial stiffness joins the bents' K0.
    std::vector<parts::Restrainer> restrainers;
    std::vector<parts::GroundLink> links;
  };

  // Throws std::invalid_argument naming the part and field ("bodies[1].mass: ...") for bad
  // parameters, indices out of range, and an initial penetration at t = 0.
  explicit Assembly(Parts parts);

  const Parts& parts() const { return parts_; }
  // The ground motions of `other` from now on, this assembly's state kept (q and u are the
  // integrator's): a system saved at t_b restarted under another excitation, e.g. the next
  // record of a sequence (docs/ground-motions.md, "Sequences"). `other` is an assembly of the
  // same parts built from other records: the same bents, seats and ground links, each support
  // moving (or fixed) as here and sharing its motion with the same supports; otherwise
  // std::invalid_argument naming what differs.
  void use_motions_of(const Assembly& other);
  // C = a0 M + a1 K0 and the assembled K0, dofs() x dofs() (zero without damping or bents).
  integrators::Matrix damping_matrix() const;
  integrators::Matrix initial_stiffness() const;
  const RayleighDamping& rayleigh_damping() const { return rayleigh_; }
  // Pose of prescribed body p at time t, with derivatives.
  PlanarMotion prescribed_motion(int p, double t) const;
  // us_dot(t) of body b: the velocity of its supports' quasi-static displacement (zero
  // without damping).
  Eigen::Vector3d quasi_static_velocity(int b, double t) const;
  // Trial spring forces of bent j from the last forces() call [kN].
  double bent_force_longitudinal(int j) const;
  double bent_force_transverse(int j) const;

  void forces(double t, const integrators::Vector& q, const integrators::Vector& u,
              integrators::Vector& f) override;
  void forces_on_committed_branches(double t, const integrators::Vector& q,
                                    const integrators::Vector& u,
                                    integrators::Vector& f) override;
  void tangent(double t, const integrators::Vector& q, const integrators::Vector& u,
               integrators::Matrix& K, integrators::Matrix& C) override;
  bool tangent_changed() const override;
  void commit() override;
  void revert() override;
  int contacts() const override { return static_cast<int>(parts_.contacts.size()); }
  void contact_data(double t, const integrators::Vector& q, const integrators::Vector& u,
                    std::vector<integrators::ContactData>& out) const override;
  // g_N, W_N, what_N and far only; prescribed faces use corner_contact_normal.
  void contact_normals(double t, const integrators::Vector& q, const integrators::Vector& u,
                       std::vector<integrators::ContactData>& out) const override;
  // damping = (u - us_dot)^T C (u - us_dot); ground = work rate of the bents' support
  // reactions on the support motion - us_dot^T C (u - us_dot). The seats' work enters through
  // the contact impulses (their rheonomic terms), which the system does not know.
  integrators::PowerTerms power(double t, const integrators::Vector& q,
                                const integrators::Vector& u) const override;
  // stored: elastic energy of the bents; hysteretic: dissipated by them (trial state).
  integrators::EnergyState energy(double t, const integrators::Vector& q) const override;

  // The output groups' columns (models/assembly_outputs.cpp, docs/outputs.md):
  //   kBents: per bent i (1-based, in the order of Parts::bents) bent<i>_ux, bent<i>_uy (its
  //     deformation: the body's displacement at the bent relative to the bent's ground, as
  //     its springs see it) and bent<i>_fx, bent<i>_fy (the force its springs exert on the
  //     body, -F of its Takeda springs at the committed state, moved to the row's deformation);
  //   kRelative: per body b x<b>_rel, y<b>_rel (its centre relative to the reference ground
  //     displacement) and corner<b>_<k>_x_rel, corner<b>_<k>_y_rel, k = 1..4 in the order of
  //     models/deck_geometry.hpp (left end +W/2, left end -W/2, right end +W/2, right end -W/2);
  //   kGround: ground_ux, ground_uy, ground_vx, ground_vy, ground_ax, ground_ay of the
  //     reference support (reference_ground()).
  std::vector<std::string> output_columns(integrators::OutputGroup g) const override;
  void output_values(integrators::OutputGroup g, double t, const integrators::Vector& q,
                     const integrators::Vector& u, double* out) const override;
  // The support whose motion the groups kRelative and kGround report: the first bent's with a
  // ground motion, else the first prescribed body's (the left seat), else none (zero).
  std::pair<parts::Motion, parts::Motion> reference_ground() const;

  // The shear keys (models/shear_keys.cpp): watch_keys updates each key's peak mean force
  // over the accepted step (normal impulse / h) and breaks it when that exceeds its capacity
  // (kContactsRemoved: the key's contact is far from then on); key_limit_states() reports one
  // "shear_key_..." limit state per key.
  integrators::StepVerdict watch_keys(const integrators::AcceptedStep& step);
  std::vector<integrators::LimitStateValue> key_limit_states() const;
  // The limit states of Parts::limits (models/limit_watch.hpp, docs/limit-states.md):
  // watch_limits updates them with an accepted step, kUnseated when a seat is lost.
  integrators::StepVerdict watch_limits(const integrators::AcceptedStep& step);
  std::vector<integrators::LimitStateValue> watched_limit_states() const;
  // Both watches, keys first; the stronger verdict (kUnseated over kContactsRemoved) wins.
  integrators::StepVerdict accept_step(const integrators::AcceptedStep& step) override;
  // The keys' limit states, then the watched ones.
  std::vector<integrators::LimitStateValue> limit_states() const override;

 private:
  // One bent, or one column of a bent with columns, with its two springs, its body's DOF
  // offset and its motions in motions_. A column (general = true) acts at point of the body
  // frame, its springs x and y along the unit directions ax and ay with the Jacobians jx and
  // jy (models/parts.hpp, Bent); a bent on the axis (general = false) is the special case
  // point = (position, 0), ax = (1, 0), ay = (0, 1), evaluated as the plain spring pair.
  struct BentState {
    int offset = 0;
    double position = 0.0;
    takeda::Spring x, y;
    int ground_x = parts::MotionTable::kNone, ground_y = parts::MotionTable::kNone;
    Eigen::Vector3d qs_x = Eigen::Vector3d::Zero(), qs_y = Eigen::Vector3d::Zero();
    bool general = false;
    Eigen::Vector2d point = Eigen::Vector2d::Zero();
    Eigen::Vector2d ax = Eigen::Vector2d::UnitX(), ay = Eigen::Vector2d::UnitY();
    Eigen::Vector3d jx = Eigen::Vector3d::UnitX(), jy = Eigen::Vector3d::UnitY();
    // The spring deformations of the state (q at the body's offset o, ground displacements).
    double deformation_x(const integrators::Vector& q, int o, double gx, double gy) const {
      return jx(0) * (q(o) - gx) + jx(1) * (q(o + 1) - gy) + jx(2) * q(o + 2);
    }
    double deformation_y(const integrators::Vector& q, int o, double gx, double gy) const {
      return jy(0) * (q(o) - gx) + jy(1) * (q(o + 1) - gy) + jy(2) * q(o + 2);
    }
  };
  // One body's share of the smooth force: its bents bents_[bent_begin, bent_end), its damping
  // block C_bb and its initial stiffness K0_bb, summed body by body into fixed-size vectors.
  struct BodyForces {
    int offset = 0;
    std::size_t bent_begin = 0, bent_end = 0;
    bool damped = false;
    Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
    Eigen::Matrix3d k0 = Eigen::Matrix3d::Zero();
  };
  struct SeatIndex {
    int x = parts::MotionTable::kNone, y = parts::MotionTable::kNone,
        phi = parts::MotionTable::kNone;
  };
  // A contact against a prescribed face, or against a body face, with its output slot.
  // rest*: the rest pose of the body at that offset (RigidBody::rest), added to q for the pose.
  struct SeatContact {
    std::size_t slot = 0;
    int offset = 0, seat = 0;
    Eigen::Vector3d rest = Eigen::Vector3d::Zero();
    CornerFace geometry;
    double restitution = 0.0, friction = 0.0, stiffness = 0.0;
    double colliding_mass = 0.0;  // [t]: ContactData::colliding_mass
  };
  // A body contact with a finite face, or one side of a joint (parts::CornerContact):
  // `partner` is the obstacle's corner against the body's face (sided only), half_length and
  // partner_half_length the extents of the two faces.
  struct BodyContact {
    std::size_t slot = 0;
    int offset_a = 0, offset_b = 0;
    Eigen::Vector3d rest_a = Eigen::Vector3d::Zero(), rest_b = Eigen::Vector3d::Zero();
    CornerFace geometry;
    double restitution = 0.0, friction = 0.0, stiffness = 0.0;
    double colliding_mass = 0.0;  // [t]: ContactData::colliding_mass
    double half_length = std::numeric_limits<double>::infinity();
    bool sided = false;
    CornerFace partner;
    double partner_half_length = std::numeric_limits<double>::infinity();
  };
  // The kinematics of a body contact's pair that is its contact (the partner's when
  // `swapped`, whose body is the obstacle: its columns' offsets are exchanged), and whether
  // it is a candidate (parts::joint_side).
  template <class Kinematics>
  struct BodyPair {
    Kinematics k;
    bool swapped = false;
    bool candidate = true;
  };
  // parts::corner_on_body or parts::corner_on_body_normal.
  template <class Kinematics>
  using CornerOnBody = Kinematics (*)(const CornerFace&, const Eigen::Vector3d&,
                                      const Eigen::Vector3d&, const Eigen::Vector3d&,
                                      const Eigen::Vector3d&);
  template <class Kinematics>
  BodyPair<Kinematics> body_pair(const BodyContact& c, const integrators::Vector& q,
                                 const integrators::Vector& u,
                                 CornerOnBody<Kinematics> kinematics) const;
  // Writes a body pair's normal fields into `out` (far when it is no candidate).
  static void write_body_pair_normal(const BodyContact& c,
                                     const BodyPair<parts::BodyContactNormal>& p,
                                     integrators::ContactData& out);

  // One shear key as the run goes: its contact's slot, the peak mean force [kN], and whether
  // and when it broke.
  struct KeyState {
    std::size_t slot = 0;
    double capacity = 0.0, peak = 0.0;
    bool broken = false;
    double time = std::numeric_limits<double>::quiet_NaN();
  };

  void validate_parts() const;
  void build_keys();  // keys_ from parts_.shear_keys, checked
  // Marks the contacts of broken keys far in `out` (after their kinematics were written).
  void mark_broken(std::vector<integrators::ContactData>& out) const {
    for (const auto& k : keys_) {
      if (k.broken) out[k.slot].far = true;
    }
  }
  void build_bents(const integrators::Matrix& mass);
  void build_damping(const integrators::Matrix& mass);
  void build_contacts();
  void check_initial_gaps() const;
  // Evaluates the motions and us_dot at t unless they are at t already (every force, contact
  // and power call of a step asks at the same t: the check is inline).
  void update_motions(double t) const {
    if (motions_.update(t)) update_quasi_static();
  }
  // update_motions(t) and the seats' poses at t, computed once per distinct t and only for
  // what reads them (contacts, connectors): a force evaluation alone does not pose the seats.
  void update_seats(double t) const {
    update_motions(t);
    if (!(seats_time_ == t)) update_seat_poses(t);
  }
  void update_quasi_static() const;  // us_dot_ from the motions' values
  void update_seat_poses(double t) const;
  // The per-step evaluations, compiled for one body (kOneBody: offset 0, 3-row columns, only
  // prescribed faces) and for any number; the public calls pick one by one_body_.
  template <bool kOneBody>
  void quasi_static() const;
  // kCommittedBranch: every spring on its committed branch, trial states left as they are.
  template <bool kOneBody, bool kCommittedBranch>
  void forces_of(double t, const integrators::Vector& q, const integrators::Vector& u,
                 integrators::Vector& f);
  template <bool kOneBody>
  void contacts_of(double t, const integrators::Vector& q, const integrators::Vector& u,
                   std::vector<integrators::ContactData>& out) const;
  template <bool kOneBody>
  void normals_of(double t, const integrators::Vector& q, const integrators::Vector& u,
                  std::vector<integrators::ContactData>& out) const;
  template <bool kOneBody>
  integrators::PowerTerms power_of(double t, const integrators::Vector& u) const;
  // Sizes `out` for contacts() entries of dofs() rows, unless it already has them.
  void size_buffer(std::vector<integrators::ContactData>& out) const {
    if (out.size() != parts_.contacts.size()) resize_buffer(out);
  }
  void resize_buffer(std::vector<integrators::ContactData>& out) const;

  Parts parts_;
  bool one_body_ = false;  // parts_.bodies.size() == 1: the evaluations compiled for one body
  // Whether accept_step has anything to watch (shear keys or limit states).
  bool watches_steps_ = false;
  bool connected_ = false;  // !connectors_.empty(): restrainers or ground links
  parts::MotionTable motions_;
  std::vector<BentState> bents_;         // grouped by body, in the given order within a body
  std::vector<std::size_t> bent_slot_;   // bents_ index of the given bent j (its first column)
  std::vector<std::size_t> bent_columns_;  // bents_ entries of the given bent j (its columns)
  std::vector<BodyForces> body_forces_;  // one per body
  std::vector<SeatIndex> seat_index_;
  std::vector<SeatContact> seat_contacts_;
  std::vector<BodyContact> body_contacts_;
  RayleighDamping rayleigh_;
  std::vector<KeyState> keys_;
  ConnectorSet connectors_;
  // Workspaces of the const evaluations, sized at construction.
  mutable std::vector<Eigen::Vector3d> us_dot_;  // us_dot per body at the motions' time
  mutable std::vector<PlanarMotion> seats_;   // prescribed poses at seats_time_
  mutable double seats_time_ = std::numeric_limits<double>::quiet_NaN();
  // The normal kinematics of every contact at one state, sized at construction when joints
  // are watched: the limit watch and contact_normals() read the same accepted state,
  // evaluated once. (t, q, u) is the state the watch evaluated them at.
  struct NormalCache {
    double t = std::numeric_limits<double>::quiet_NaN();
    integrators::Vector q, u;
    std::vector<ContactNormal> seat;             // per seat_contacts_
    std::vector<BodyPair<parts::BodyContactNormal>> body;  // per body_contacts_
  };
  mutable NormalCache normals_;
  void evaluate_normals(double t, const integrators::Vector& q,
                        const integrators::Vector& u) const;
  // Whether normals_ holds (t, q, u) as the watch left it (bit for bit).
  bool normals_at(double t, const integrators::Vector& q, const integrators::Vector& u) const;
  // The watched limit states and the contact gaps they read, sized at construction.
  LimitWatch watch_;
  std::vector<double> watch_gaps_;
  void build_limits();
  void watch_gaps(double t, const integrators::Vector& q, const integrators::Vector& u);
};

}  // namespace nsb::models
