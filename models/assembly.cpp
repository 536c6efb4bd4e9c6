#include "models/assembly.hpp"
#include "models/deck_geometry.hpp"
#include "models/field_checks.hpp"

#include <cmath>
#include <cstring>
#include <initializer_list>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace nsb::models {

namespace {

// The body frame's x of its axis's midpoint: -xbar of a body whose end angles differ
// (DeckGeometry::axis_centre), 0 otherwise.
double axis_centre_x(const parts::RigidBody& b) {
  const DeckGeometry plan{.length = b.length, .width = b.width, .skew_deg = b.skew_deg,
                          .gap_right = 0.0, .gap_left = 0.0, .skew_left_deg = b.skew_left_deg,
                          .skew_right_deg = b.skew_right_deg, .radius = b.radius};
  return plan.axis_centre().x();
}

// Coordinate names: x, y, theta for one body, x1, y1, theta1, ... for several.
std::vector<std::string> names(std::size_t bodies, std::initializer_list<const char*> base) {
  std::vector<std::string> out;
  for (std::size_t b = 0; b < bodies; ++b) {
    for (const char* n : base) {
      out.push_back(bodies == 1 ? std::string(n) : n + std::to_string(b + 1));
    }
  }
  return out;
}

void validate_takeda(const takeda::Parameters& p, const std::string& field) {
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(field + "." + e.what());
  }
}

}  // namespace

Assembly::Assembly(Parts parts)
    : SystemBase(names(parts.bodies.size(), {"x", "y", "theta"}),
                 names(parts.bodies.size(), {"vx", "vy", "omega"})),
      parts_(std::move(parts)) {
  validate_parts();
  build_keys();
  const auto n = static_cast<Eigen::Index>(3 * parts_.bodies.size());
  integrators::Matrix mass = integrators::Matrix::Zero(n, n);
  integrators::Vector q0(n), u0(n);
  for (std::size_t b = 0; b < parts_.bodies.size(); ++b) {
    const auto& body = parts_.bodies[b];
    const auto o = static_cast<Eigen::Index>(3 * b);
    mass(o, o) = mass(o + 1, o + 1) = body.mass;
    mass(o + 2, o + 2) = body.inertia;
    q0.segment<3>(o) = body.initial_position;
    u0.segment<3>(o) = body.initial_velocity;
  }
  set_mass(mass);
  set_initial_state(q0, u0);
  connectors_ = ConnectorSet(parts_.bodies, parts_.prescribed, parts_.restrainers, parts_.links,
                             motions_);
  connected_ = !connectors_.empty();
  build_bents(mass);
  build_contacts();
  // The seats at rest. A component without a motion keeps this value (update_seat_poses moves
  // the others); + 0.0 is the zero displacement update_seat_poses would add.
  seats_.assign(parts_.prescribed.size(), PlanarMotion{});
  for (std::size_t p = 0; p < seats_.size(); ++p) {
    const Eigen::Vector2d& a = parts_.prescribed[p].reference;
    seats_[p].position << a.x() + 0.0, a.y() + 0.0, 0.0;
  }
  one_body_ = parts_.bodies.size() == 1;
  check_initial_gaps();
  build_limits();
  watches_steps_ = !keys_.empty() || !watch_.empty();
}

void Assembly::validate_parts() const {
  const auto nb = static_cast<int>(parts_.bodies.size());
  require(nb >= 1, "bodies", "at least one rigid body is needed");
  for (std::size_t b = 0; b < parts_.bodies.size(); ++b) {
    parts_.bodies[b].validate(indexed("bodies", b));
  }
  for (std::size_t j = 0; j < parts_.bents.size(); ++j) {
    const auto& bent = parts_.bents[j];
    const std::string prefix = indexed("bents", j);
    require(bent.body >= 0 && bent.body < nb, prefix + "body", "must name one of the bodies");
    // s is measured from the centroid, which lies off the axis's midpoint where the two end
    // angles differ (models/deck_geometry.hpp). A curved body's bent lines cross its chord
    // axis beyond L/2 near its ends (DeckGeometry::bent_site); their arc positions are
    // checked by the bridge's design.
    const auto& body = parts_.bodies[static_cast<std::size_t>(bent.body)];
    require(std::isfinite(bent.position) &&
                (body.radius > 0 ||
                 std::abs(bent.position - axis_centre_x(body)) <= 0.5 * body.length),
            prefix + "position", "must lie on the body, |s| <= L/2 [m]");
    validate_takeda(bent.longitudinal, prefix + "longitudinal");
    validate_takeda(bent.transverse, prefix + "transverse");
    for (const double e : bent.column_offsets) {
      require(std::isfinite(e), prefix + "column_offsets", "must be finite [m]");
    }
    require(std::isfinite(bent.skew_deg) && std::abs(bent.skew_deg) < 80.0, prefix + "skew_deg",
            "must be in (-80, 80) [deg]");
  }
  const auto np = static_cast<int>(parts_.prescribed.size());
  for (std::size_t i = 0; i < parts_.contacts.size(); ++i) {
    const auto& c = parts_.contacts[i];
    const std::string prefix = indexed("contacts", i);
    require(c.body >= 0 && c.body < nb, prefix + "body", "must name one of the bodies");
    require(c.corner >= 0 && c.corner <= 3, prefix + "corner", "must be 0, 1, 2 or 3");
    const bool on_body = c.obstacle == parts::Obstacle::kBody;
    require(c.obstacle_index >= 0 && c.obstacle_index < (on_body ? nb : np),
            prefix + "obstacle_index",
            on_body ? "must name one of the bodies" : "must name one of the prescribed bodies");
    require(!on_body || c.obstacle_index != c.body, prefix + "obstacle_index",
            "must be another body than the corner's");
    require(c.face.point.allFinite(), prefix + "face.point", "must be finite [m]");
    require(c.face.normal.allFinite() && std::abs(c.face.normal.norm() - 1.0) < 1e-12,
            prefix + "face.normal", "must be a unit vector");
    require(c.face.half_length > 0, prefix + "face.half_length", "must be > 0 [m]");
    require(c.partner_corner < 0 || (on_body && c.partner_corner <= 3 &&
                                     c.partner_face.half_length > 0 &&
                                     std::abs(c.partner_face.normal.norm() - 1.0) < 1e-12),
            prefix + "partner_corner",
            "must be -1, or 0..3 against another body with a partner face");
    require(std::isfinite(c.restitution) && c.restitution >= 0 && c.restitution <= 1,
            prefix + "restitution", "must be in [0, 1]");
    require(std::isfinite(c.friction) && c.friction >= 0, prefix + "friction", "must be >= 0");
    require(std::isfinite(c.stiffness) && c.stiffness >= 0, prefix + "stiffness",
            "must be >= 0 [kN/m^1.5] (0: solver.contact_stiffness)");
  }
}

void Assembly::build_bents(const integrators::Matrix& mass) {
  body_forces_.resize(parts_.bodies.size());
  bent_slot_.resize(parts_.bents.size());
  bent_columns_.resize(parts_.bents.size());
  for (std::size_t i = 0; i < body_forces_.size(); ++i) {
    BodyForces& body = body_forces_[i];
    body.offset = static_cast<int>(3 * i);
    body.bent_begin = bents_.size();
    for (std::size_t j = 0; j < parts_.bents.size(); ++j) {
      const auto& p = parts_.bents[j];
      if (static_cast<std::size_t>(p.body) != i) continue;
      bent_slot_[j] = bents_.size();
      const int ground_x = motions_.add(p.ground_longitudinal, false);
      const int ground_y = motions_.add(p.ground_transverse, false);
      if (p.column_offsets.empty() && p.skew_deg == 0.0) {
        bent_columns_[j] = 1;
        bents_.push_back({.offset = body.offset, .position = p.position,
                          .x = takeda::Spring(p.longitudinal), .y = takeda::Spring(p.transverse),
                          .ground_x = ground_x, .ground_y = ground_y});
        // K0 += k0_x b_x b_x^T + k0_y b_y b_y^T.
        const Eigen::Vector3d by(0.0, 1.0, p.position);
        body.k0(0, 0) += p.longitudinal.k0;
        body.k0 += p.transverse.k0 * by * by.transpose();
        continue;
      }
      // The columns (models/parts.hpp, Bent): each 1/n of both springs at its own point.
      const std::vector<double> offsets =
          p.column_offsets.empty() ? std::vector<double>{0.0} : p.column_offsets;
      const double share = 1.0 / static_cast<double>(offsets.size());
      const auto column_spring = [share](takeda::Parameters k) {
        k.k0 *= share;
        k.f_crack *= share;
        k.f_yield *= share;
        return k;
      };
      const double beta = p.skew_deg * std::numbers::pi / 180.0;
      const Eigen::Vector2d n(std::cos(beta), -std::sin(beta));
      const Eigen::Vector2d t(std::sin(beta), std::cos(beta));
      bent_columns_[j] = offsets.size();
      for (const double e : offsets) {
        BentState c{.offset = body.offset, .position = p.position,
                    .x = takeda::Spring(column_spring(p.longitudinal)),
                    .y = takeda::Spring(column_spring(p.transverse)), .ground_x = ground_x,
                    .ground_y = ground_y};
        c.general = true;
        c.point = Eigen::Vector2d(p.position + e * std::tan(beta), e);
        c.ax = n;
        c.ay = t;
        c.jx = Eigen::Vector3d(n.x(), n.y(), n.y() * c.point.x() - n.x() * c.point.y());
        c.jy = Eigen::Vector3d(t.x(), t.y(), t.y() * c.point.x() - t.x() * c.point.y());
        body.k0 += c.x.parameters().k0 * c.jx * c.jx.transpose() +
                   c.y.parameters().k0 * c.jy * c.jy.transpose();
        bents_.push_back(std::move(c));
      }
    }
    body.bent_end = bents_.size();
    connectors_.add_initial_stiffness(static_cast<int>(i), body.k0);
  }
  us_dot_.assign(body_forces_.size(), Eigen::Vector3d::Zero());
  if (parts_.damping) build_damping(mass);
}

void Assembly::build_damping(const integrators::Matrix& mass) {
  const auto& d = *parts_.damping;
  integrators::Matrix k0 = integrators::Matrix::Zero(mass.rows(), mass.cols());
  for (const auto& b : body_forces_) k0.block<3, 3>(b.offset, b.offset) = b.k0;
  try {
    rayleigh_ = rayleigh(mass, k0, d.mode_i, d.ratio_i, d.mode_j, d.ratio_j);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("damping: ") + e.what());
  }
  for (auto& b : body_forces_) {
    b.damped = true;
    b.c = rayleigh_.a0 * mass.block<3, 3>(b.offset, b.offset) + rayleigh_.a1 * b.k0;
    // us = sum_j (qs_x u_gx,j + qs_y u_gy,j), qs the columns K0_bb^-1 k0_j b_j.
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(b.k0);
    for (std::size_t j = b.bent_begin; j < b.bent_end; ++j) {
      BentState& bent = bents_[j];
      if (bent.general) {
        // d f / d u_g = k0_x a_x J_x + k0_y a_y J_y per ground direction.
        const double kx = bent.x.parameters().k0, ky = bent.y.parameters().k0;
        bent.qs_x = ldlt.solve(kx * bent.ax.x() * bent.jx + ky * bent.ay.x() * bent.jy);
        bent.qs_y = ldlt.solve(kx * bent.ax.y() * bent.jx + ky * bent.ay.y() * bent.jy);
        continue;
      }
      bent.qs_x = ldlt.solve(Eigen::Vector3d(bent.x.parameters().k0, 0.0, 0.0));
      bent.qs_y =
          ldlt.solve(bent.y.parameters().k0 * Eigen::Vector3d(0.0, 1.0, bent.position));
    }
    connectors_.set_quasi_static(b.offset / 3, ldlt);
  }
}

void Assembly::build_contacts() {
  for (const auto& p : parts_.prescribed) {
    seat_index_.push_back({motions_.add(p.longitudinal, true), motions_.add(p.transverse, true),
                           motions_.add(p.rotation, true)});
  }
  for (std::size_t i = 0; i < parts_.contacts.size(); ++i) {
    const auto& c = parts_.contacts[i];
    const CornerFace geometry{
        .body_point = parts_.bodies[static_cast<std::size_t>(c.body)].corner(c.corner),
        .face_point = c.face.point, .face_normal = c.face.normal};
    // The mass the contact stops, which scales the compliance method's default Hertz k: the
    // body's own against a prescribed face (a seat or a key moves with the ground, whatever
    // the force), the reduced mass m_a m_b / (m_a + m_b) of a two-body impact otherwise.
    const double m_a = parts_.bodies[static_cast<std::size_t>(c.body)].mass;
    if (c.obstacle == parts::Obstacle::kPrescribed) {
      seat_contacts_.push_back({.slot = i, .offset = 3 * c.body, .seat = c.obstacle_index,
                                .rest = parts_.bodies[static_cast<std::size_t>(c.body)].rest,
                                .geometry = geometry, .restitution = c.restitution,
                                .friction = c.friction, .stiffness = c.stiffness,
                                .colliding_mass = m_a});
    } else {
      const auto& other = parts_.bodies[static_cast<std::size_t>(c.obstacle_index)];
      const double m_b = other.mass;
      BodyContact b{.slot = i, .offset_a = 3 * c.body, .offset_b = 3 * c.obstacle_index,
                    .rest_a = parts_.bodies[static_cast<std::size_t>(c.body)].rest,
                    .rest_b = other.rest, .geometry = geometry,
                    .restitution = c.restitution, .friction = c.friction,
                    .stiffness = c.stiffness, .colliding_mass = m_a * m_b / (m_a + m_b),
                    .half_length = c.face.half_length,
                    .sided = false, .partner = {},
                    .partner_half_length = std::numeric_limits<double>::infinity()};
      if (c.partner_corner >= 0) {
        b.sided = true;
        b.partner = {.body_point = other.corner(c.partner_corner),
                     .face_point = c.partner_face.point, .face_normal = c.partner_face.normal};
        b.partner_half_length = c.partner_face.half_length;
      }
      body_contacts_.push_back(b);
    }
  }
}

void Assembly::check_initial_gaps() const {
  std::vector<integrators::ContactData> c = make_contact_buffer();
  contact_data(initial_time(), initial_position(), initial_velocity(), c);
  for (std::size_t i = 0; i < c.size(); ++i) {
    // A contact that is no candidate (a corner beyond a face's end) cannot penetrate.
    if (!c[i].far && c[i].gap_normal < -kPenetrationTolerance) {
      std::ostringstream s;
      s << "contacts[" << i << "]: initial penetration (g_N = " << c[i].gap_normal
        << " m); the initial gaps must be >= 0";
      throw std::invalid_argument(s.str());
    }
  }
}

void Assembly::update_quasi_static() const {
  if (one_body_) {
    quasi_static<true>();
  } else {
    quasi_static<false>();
  }
}

template <bool kOneBody>
void Assembly::quasi_static() const {
  const std::size_t bodies = kOneBody ? 1 : body_forces_.size();
  for (std::size_t i = 0; i < bodies; ++i) {
    const BodyForces& body = body_forces_[i];
    if (!body.damped) continue;
    Eigen::Vector3d us = Eigen::Vector3d::Zero();
    for (std::size_t j = body.bent_begin; j < body.bent_end; ++j) {
      const BentState& b = bents_[j];
      us += b.qs_x * motions_.value(b.ground_x).v + b.qs_y * motions_.value(b.ground_y).v;
    }
    if (connected_) connectors_.add_support_velocity(static_cast<int>(i), motions_, us);
    us_dot_[i] = us;
  }
}

void Assembly::update_seat_poses(double t) const {
  for (std::size_t p = 0; p < seats_.size(); ++p) {
    const SeatIndex& ix = seat_index_[p];
    const Eigen::Vector2d& a = parts_.prescribed[p].reference;
    PlanarMotion& m = seats_[p];
    // Only the components with a motion move (a seat driven along x alone moves in x only).
    if (ix.x != parts::MotionTable::kNone) {
      const auto& mx = motions_.value(ix.x);
      m.position.x() = a.x() + mx.d;
      m.velocity.x() = mx.v;
      m.acceleration.x() = mx.a;
    }
    if (ix.y != parts::MotionTable::kNone) {
      const auto& my = motions_.value(ix.y);
      m.position.y() = a.y() + my.d;
      m.velocity.y() = my.v;
      m.acceleration.y() = my.a;
    }
    if (ix.phi != parts::MotionTable::kNone) {
      const auto& mr = motions_.value(ix.phi);
      m.position.z() = mr.d;
      m.velocity.z() = mr.v;
      m.acceleration.z() = mr.a;
    }
  }
  seats_time_ = t;
}

PlanarMotion Assembly::prescribed_motion(int p, double t) const {
  update_seats(t);
  return seats_.at(static_cast<std::size_t>(p));
}

Eigen::Vector3d Assembly::quasi_static_velocity(int b, double t) const {
  update_motions(t);
  return us_dot_.at(static_cast<std::size_t>(b));
}

integrators::Matrix Assembly::damping_matrix() const {
  integrators::Matrix c = integrators::Matrix::Zero(dofs(), dofs());
  for (const auto& b : body_forces_) c.block<3, 3>(b.offset, b.offset) = b.c;
  return c;
}

integrators::Matrix Assembly::initial_stiffness() const {
  integrators::Matrix k = integrators::Matrix::Zero(dofs(), dofs());
  for (const auto& b : body_forces_) k.block<3, 3>(b.offset, b.offset) = b.k0;
  return k;
}

double Assembly::bent_force_longitudinal(int j) const {
  const std::size_t first = bent_slot_.at(static_cast<std::size_t>(j));
  double f = bents_[first].x.force();
  for (std::size_t c = 1; c < bent_columns_[static_cast<std::size_t>(j)]; ++c) {
    f += bents_[first + c].x.force();
  }
  return f;
}

double Assembly::bent_force_transverse(int j) const {
  const std::size_t first = bent_slot_.at(static_cast<std::size_t>(j));
  double f = bents_[first].y.force();
  for (std::size_t c = 1; c < bent_columns_[static_cast<std::size_t>(j)]; ++c) {
    f += bents_[first + c].y.force();
  }
  return f;
}

void Assembly::forces(double t, const integrators::Vector& q, const integrators::Vector& u,
                      integrators::Vector& f) {
  if (one_body_) {
    forces_of<true, false>(t, q, u, f);
  } else {
    forces_of<false, false>(t, q, u, f);
  }
}

void Assembly::forces_on_committed_branches(double t, const integrators::Vector& q,
                                            const integrators::Vector& u,
                                            integrators::Vector& f) {
  if (one_body_) {
    forces_of<true, true>(t, q, u, f);
  } else {
    forces_of<false, true>(t, q, u, f);
  }
}

template <bool kOneBody, bool kCommittedBranch>
void Assembly::forces_of(double t, const integrators::Vector& q, const integrators::Vector& u,
                         integrators::Vector& f) {
  update_motions(t);
  const std::size_t bodies = kOneBody ? 1 : body_forces_.size();
  for (std::size_t i = 0; i < bodies; ++i) {
    const BodyForces& body = body_forces_[i];
    const int o = kOneBody ? 0 : body.offset;  // the bents of a body share its offset
    Eigen::Vector3d fs = Eigen::Vector3d::Zero();
    for (std::size_t j = body.bent_begin; j < body.bent_end; ++j) {
      BentState& b = bents_[j];
      if (b.general) {
        const double gx = motions_.value(b.ground_x).d, gy = motions_.value(b.ground_y).d;
        const double dx = b.deformation_x(q, o, gx, gy), dy = b.deformation_y(q, o, gx, gy);
        const double fx = kCommittedBranch ? b.x.force_on_committed_branch(dx) : b.x.set_trial(dx);
        const double fy = kCommittedBranch ? b.y.force_on_committed_branch(dy) : b.y.set_trial(dy);
        fs -= fx * b.jx + fy * b.jy;
        continue;
      }
      const double s = b.position;
      // Body displacement at the bent relative to the bent's own ground (small rotations).
      const double dx = q(o) - motions_.value(b.ground_x).d;
      const double dy = q(o + 1) + s * q(o + 2) - motions_.value(b.ground_y).d;
      const double fx = kCommittedBranch ? b.x.force_on_committed_branch(dx) : b.x.set_trial(dx);
      const double fy = kCommittedBranch ? b.y.force_on_committed_branch(dy) : b.y.set_trial(dy);
      fs(0) -= fx;
      fs(1) -= fy;
      fs(2) -= s * fy;  // torque of the transverse bent force about the body centre
    }
    if (body.damped) {
      const Eigen::Vector3d vr = u.segment<3>(o) - us_dot_[i];
      f.segment<3>(o) = fs - body.c * vr;
    } else {
      f.segment<3>(o) = fs;
    }
  }
  if (connected_) {
    update_seats(t);
    if constexpr (kCommittedBranch) {
      connectors_.forces_on_committed_branches(q, motions_, seats_, f);
    } else {
      connectors_.forces(q, motions_, seats_, f);
    }
  }
}

void Assembly::tangent(double, const integrators::Vector&, const integrators::Vector&,
                       integrators::Matrix& K, integrators::Matrix& C) {
  K.setZero(dofs(), dofs());
  for (const auto& b : bents_) {
    const double s = b.position;
    const int o = b.offset;
    const double kx = b.x.tangent(), ky = b.y.tangent();
    if (b.general) {
      K.block<3, 3>(o, o) += kx * b.jx * b.jx.transpose() + ky * b.jy * b.jy.transpose();
      continue;
    }
    K(o, o) += kx;
    K(o + 1, o + 1) += ky;
    K(o + 1, o + 2) += ky * s;
    K(o + 2, o + 1) += ky * s;
    K(o + 2, o + 2) += ky * s * s;
  }
  if (connected_) connectors_.tangent(K);
  C.setZero(dofs(), dofs());
  for (const auto& b : body_forces_) C.block<3, 3>(b.offset, b.offset) = b.c;
}

bool Assembly::tangent_changed() const {
  for (const auto& b : bents_) {
    if (b.x.tangent_changed() || b.y.tangent_changed()) return true;
  }
  return connected_ && connectors_.tangent_changed();
}

void Assembly::commit() {
  for (auto& b : bents_) b.x.commit();
  for (auto& b : bents_) b.y.commit();
  if (connected_) connectors_.commit();
}

void Assembly::revert() {
  for (auto& b : bents_) b.x.revert();
  for (auto& b : bents_) b.y.revert();
  if (connected_) connectors_.revert();
}

void Assembly::resize_buffer(std::vector<integrators::ContactData>& out) const {
  out.resize(parts_.contacts.size());
  for (auto& c : out) {
    c.w_normal = integrators::Vector::Zero(dofs());
    c.w_tangent = integrators::Vector::Zero(dofs());
  }
}

void Assembly::contact_data(double t, const integrators::Vector& q, const integrators::Vector& u,
                            std::vector<integrators::ContactData>& out) const {
  if (one_body_) {
    contacts_of<true>(t, q, u, out);
  } else {
    contacts_of<false>(t, q, u, out);
  }
}

template <bool kOneBody>
void Assembly::contacts_of(double t, const integrators::Vector& q, const integrators::Vector& u,
                           std::vector<integrators::ContactData>& out) const {
  size_buffer(out);
  update_seats(t);
  // The corners of one body are consecutive: its state is copied once for them.
  Eigen::Vector3d qa, ua;
  int body = -1;
  for (const auto& c : seat_contacts_) {
    const int offset = kOneBody ? 0 : c.offset;
    if (offset != body) {
      body = offset;
      qa = q.segment<3>(body) + c.rest;
      ua = u.segment<3>(body);
    }
    const auto k = corner_contact(c.geometry, qa, ua, seats_[static_cast<std::size_t>(c.seat)]);
    parts::write_contact(k, offset, c.restitution, c.friction, out[c.slot]);
    out[c.slot].stiffness = c.stiffness;
    out[c.slot].colliding_mass = c.colliding_mass;
  }
  if (!kOneBody) {  // a contact against a body needs two
    for (const auto& c : body_contacts_) {
      const auto p = body_pair(c, q, u, parts::corner_on_body);
      parts::write_body_contact(p.k, p.swapped ? c.offset_b : c.offset_a,
                                p.swapped ? c.offset_a : c.offset_b, c.restitution, c.friction,
                                out[c.slot]);
      out[c.slot].stiffness = c.stiffness;
      out[c.slot].colliding_mass = c.colliding_mass;
      if (!p.candidate) out[c.slot].far = true;
    }
  }
  mark_broken(out);
}

namespace {

// Bitwise equality of two vectors of the same size (NaN equals NaN, -0 differs from +0): the
// cached normals are reused only for exactly the state they were computed from.
bool same_bits(const integrators::Vector& a, const integrators::Vector& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) ==
             0;
}

}  // namespace

void Assembly::use_motions_of(const Assembly& other) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("Assembly::use_motions_of: " + what + " differ");
  };
  if (other.parts_.bents.size() != parts_.bents.size() ||
      other.parts_.prescribed.size() != parts_.prescribed.size() ||
      other.parts_.links.size() != parts_.links.size() || other.dofs() != dofs()) {
    fail("the parts");
  }
  // Equal indices into equally long tables: every support reads the motion at the same place.
  if (other.motions_.size() != motions_.size()) fail("the numbers of distinct motions");
  for (std::size_t i = 0; i < bents_.size(); ++i) {
    if (other.bents_[i].ground_x != bents_[i].ground_x ||
        other.bents_[i].ground_y != bents_[i].ground_y) {
      fail("the bents' support motions");
    }
  }
  for (std::size_t p = 0; p < seat_index_.size(); ++p) {
    const SeatIndex &a = seat_index_[p], &b = other.seat_index_[p];
    if (a.x != b.x || a.y != b.y || a.phi != b.phi) fail("the seats' motions");
  }
  for (std::size_t l = 0; l < parts_.links.size(); ++l) {
    const parts::GroundLink &a = parts_.links[l], &b = other.parts_.links[l];
    if (!a.ground_longitudinal != !b.ground_longitudinal ||
        !a.ground_transverse != !b.ground_transverse) {
      fail("the ground links' motions");
    }
  }
  for (std::size_t j = 0; j < parts_.bents.size(); ++j) {
    parts_.bents[j].ground_longitudinal = other.parts_.bents[j].ground_longitudinal;
    parts_.bents[j].ground_transverse = other.parts_.bents[j].ground_transverse;
  }
  for (std::size_t p = 0; p < parts_.prescribed.size(); ++p) {
    parts_.prescribed[p].longitudinal = other.parts_.prescribed[p].longitudinal;
    parts_.prescribed[p].transverse = other.parts_.prescribed[p].transverse;
    parts_.prescribed[p].rotation = other.parts_.prescribed[p].rotation;
  }
  for (std::size_t l = 0; l < parts_.links.size(); ++l) {
    parts_.links[l].ground_longitudinal = other.parts_.links[l].ground_longitudinal;
    parts_.links[l].ground_transverse = other.parts_.links[l].ground_transverse;
  }
  // The evaluations cached at a time were of the old motions.
  motions_ = other.motions_;
  motions_.invalidate();
  seats_time_ = std::numeric_limits<double>::quiet_NaN();
  normals_.t = std::numeric_limits<double>::quiet_NaN();
}

bool Assembly::normals_at(double t, const integrators::Vector& q,
                          const integrators::Vector& u) const {
  return std::memcmp(&t, &normals_.t, sizeof t) == 0 && same_bits(q, normals_.q) &&
         same_bits(u, normals_.u);
}

void Assembly::evaluate_normals(double t, const integrators::Vector& q,
                                const integrators::Vector& u) const {
  update_seats(t);
  Eigen::Vector3d qa, ua;
  int body = -1;
  for (std::size_t i = 0; i < seat_contacts_.size(); ++i) {
    const SeatContact& c = seat_contacts_[i];
    if (c.offset != body) {
      body = c.offset;
      qa = q.segment<3>(body) + c.rest;
      ua = u.segment<3>(body);
    }
    normals_.seat[i] =
        corner_contact_normal(c.geometry, qa, ua, seats_[static_cast<std::size_t>(c.seat)]);
  }
  for (std::size_t i = 0; i < body_contacts_.size(); ++i) {
    normals_.body[i] = body_pair(body_contacts_[i], q, u, parts::corner_on_body_normal);
  }
}

void Assembly::contact_normals(double t, const integrators::Vector& q,
                               const integrators::Vector& u,
                               std::vector<integrators::ContactData>& out) const {
  size_buffer(out);
  if (watch_.watches_joints() && normals_at(t, q, u)) {
    // The limit watch evaluated them at this accepted state.
    for (std::size_t i = 0; i < seat_contacts_.size(); ++i) {
      const SeatContact& c = seat_contacts_[i];
      parts::write_contact_normal(normals_.seat[i], c.offset, out[c.slot]);
    }
    for (std::size_t i = 0; i < body_contacts_.size(); ++i) {
      write_body_pair_normal(body_contacts_[i], normals_.body[i], out[body_contacts_[i].slot]);
    }
    mark_broken(out);
    return;
  }
  if (one_body_) {
    normals_of<true>(t, q, u, out);
  } else {
    normals_of<false>(t, q, u, out);
  }
}

template <bool kOneBody>
void Assembly::normals_of(double t, const integrators::Vector& q, const integrators::Vector& u,
                          std::vector<integrators::ContactData>& out) const {
  update_seats(t);
  Eigen::Vector3d qa, ua;
  int body = -1;
  for (const auto& c : seat_contacts_) {
    const int offset = kOneBody ? 0 : c.offset;
    if (offset != body) {
      body = offset;
      qa = q.segment<3>(body) + c.rest;
      ua = u.segment<3>(body);
    }
    const auto k =
        corner_contact_normal(c.geometry, qa, ua, seats_[static_cast<std::size_t>(c.seat)]);
    parts::write_contact_normal(k, offset, out[c.slot]);
  }
  if (!kOneBody) {
    for (const auto& c : body_contacts_) {
      write_body_pair_normal(c, body_pair(c, q, u, parts::corner_on_body_normal), out[c.slot]);
    }
  }
  mark_broken(out);
}

// The pair of a body contact that is its contact (docs/bridge.md, "Contacts with edges"):
// a contact without a partner is its own pair, a candidate while its corner lies on the face;
// one side of a joint is the pair whose corner lies further inside the other's face
// (parts::joint_side), the partner's with the bodies exchanged. `kinematics` is
// parts::corner_on_body (the full kinematics) or parts::corner_on_body_normal (its normal part).
template <class Kinematics>
Assembly::BodyPair<Kinematics> Assembly::body_pair(const BodyContact& c,
                                                   const integrators::Vector& q,
                                                   const integrators::Vector& u,
                                                   CornerOnBody<Kinematics> kinematics) const {
  const Eigen::Vector3d qa = q.segment<3>(c.offset_a) + c.rest_a;
  const Eigen::Vector3d qb = q.segment<3>(c.offset_b) + c.rest_b;
  BodyPair<Kinematics> p;
  p.k = kinematics(c.geometry, qa, u.segment<3>(c.offset_a), qb, u.segment<3>(c.offset_b));
  const double first = parts::beyond_edge(p.k.a.gap_tangent, c.half_length);
  if (!c.sided) {
    p.candidate = first <= parts::kEdgeTie;
    return p;
  }
  auto partner = kinematics(c.partner, qb, u.segment<3>(c.offset_b), qa, u.segment<3>(c.offset_a));
  const parts::JointSide side = parts::joint_side(
      first, parts::beyond_edge(partner.a.gap_tangent, c.partner_half_length),
      p.k.a.gap_normal, partner.a.gap_normal);
  if (side.second) {
    p.k = partner;
    p.swapped = true;
  }
  p.candidate = side.candidate;
  return p;
}

void Assembly::write_body_pair_normal(const BodyContact& c,
                                      const BodyPair<parts::BodyContactNormal>& p,
                                      integrators::ContactData& out) {
  parts::write_body_contact_normal(p.k, p.swapped ? c.offset_b : c.offset_a,
                                   p.swapped ? c.offset_a : c.offset_b, out);
  if (!p.candidate) out.far = true;
}

integrators::PowerTerms Assembly::power(double t, const integrators::Vector&,
                                        const integrators::Vector& u) const {
  return one_body_ ? power_of<true>(t, u) : power_of<false>(t, u);
}

template <bool kOneBody>
integrators::PowerTerms Assembly::power_of(double t, const integrators::Vector& u) const {
  integrators::PowerTerms pw;
  update_motions(t);
  double ground = 0.0;
  const std::size_t bodies = kOneBody ? 1 : body_forces_.size();
  for (std::size_t i = 0; i < bodies; ++i) {
    const BodyForces& body = body_forces_[i];
    if (!body.damped) continue;
    const Eigen::Vector3d& us = us_dot_[i];
    const Eigen::Vector3d vr = u.segment<3>(kOneBody ? 0 : body.offset) - us;
    const Eigen::Vector3d cvr = body.c * vr;
    pw.damping += vr.dot(cvr);
    ground -= us.dot(cvr);
  }
  for (const auto& b : bents_) {
    if (b.general) {
      const Eigen::Vector2d f = b.x.force() * b.ax + b.y.force() * b.ay;
      ground -= f.x() * motions_.value(b.ground_x).v + f.y() * motions_.value(b.ground_y).v;
      continue;
    }
    ground -= b.x.force() * motions_.value(b.ground_x).v +
              b.y.force() * motions_.value(b.ground_y).v;
  }
  if (connected_) {
    update_seats(t);
    ground += connectors_.ground_power(motions_, seats_);
  }
  pw.ground = ground;
  return pw;
}

integrators::EnergyState Assembly::energy(double, const integrators::Vector&) const {
  integrators::EnergyState e;
  for (const auto& b : bents_) {
    e.stored += b.x.stored_energy() + b.y.stored_energy();
    e.hysteretic += b.x.dissipated_energy() + b.y.dissipated_energy();
  }
  if (connected_) connectors_.energy(e);
  return e;
}

}  // namespace nsb::models
