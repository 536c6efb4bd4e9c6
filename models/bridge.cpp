#include "models/bridge.hpp"
#include "models/field_checks.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace nsb::models {

namespace {

bool finite_positive(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

// ---------------------------------------------------------------------------------------------
// BentDesign

void BentDesign::validate(const std::string& prefix) const {
  require(finite_positive(height), prefix + "height", "must be > 0 [m]");
  require(finite_positive(column_diameter), prefix + "column_diameter", "must be > 0 [m]");
  require(columns >= 1, prefix + "columns", "must be >= 1");
  require(finite_positive(elastic_modulus), prefix + "elastic_modulus", "must be > 0 [kPa]");
  require(finite_positive(cracked_ratio) && cracked_ratio <= 1, prefix + "cracked_ratio",
          "must be in (0, 1]");
  require(finite_positive(yield_strain), prefix + "yield_strain", "must be > 0");
  require(std::isfinite(post_yield_ratio) && post_yield_ratio >= 0 && post_yield_ratio < 1,
          prefix + "post_yield_ratio", "must be in [0, 1)");
  require(std::isfinite(unloading_exponent) && unloading_exponent >= 0 && unloading_exponent <= 1,
          prefix + "unloading_exponent", "must be in [0, 1]");
}

double BentDesign::column_stiffness() const {
  const double d2 = column_diameter * column_diameter;
  const double ei = cracked_ratio * elastic_modulus * std::numbers::pi * d2 * d2 / 64.0;
  return 12.0 * ei / (height * height * height);  // fixed-fixed column
}

double BentDesign::stiffness() const { return columns * column_stiffness(); }

double BentDesign::yield_displacement() const {
  const double phi_y = 2.25 * yield_strain / column_diameter;  // Priestley's yield curvature
  return phi_y * height * height / 6.0;
}

double BentDesign::yield_force() const { return stiffness() * yield_displacement(); }

takeda::Parameters BentDesign::takeda() const {
  return takeda::Parameters::bilinear(yield_force(), yield_displacement(), post_yield_ratio,
                                      unloading_exponent);
}

// ---------------------------------------------------------------------------------------------
// Parameters

Bridge::Parameters Bridge::Parameters::benchmark() {
  Parameters p;
  const double span = 0.25 * p.deck.length;  // four equal spans (assumed, docs/bridge.md)
  const double positions[3] = {-span, 0.0, span};
  const double heights[3] = {1.83, 2.44, 1.52};    // assumed, docs/bridge.md
  for (int j = 0; j < 3; ++j) {
    BentDesign d;
    d.height = heights[j];
    Bent b;
    b.position = positions[j];
    b.longitudinal = d.takeda();
    b.transverse = d.takeda();
    p.bents.push_back(b);
  }
  return p;
}

void Bridge::Parameters::validate() const {
  require(finite_positive(mass), "mass", "must be > 0 [t]");
  require(finite_positive(inertia), "inertia", "must be > 0 [t m^2]");
  deck.validate();
  require(std::isfinite(restitution) && restitution >= 0 && restitution <= 1, "restitution",
          "must be in [0, 1]");
  require(std::isfinite(friction) && friction >= 0, "friction", "must be >= 0");
  require(std::isfinite(damping_ratio_i) && damping_ratio_i >= 0 && damping_ratio_i < 1,
          "damping_ratio_i", "must be in [0, 1)");
  require(std::isfinite(damping_ratio_j) && damping_ratio_j >= 0 && damping_ratio_j < 1,
          "damping_ratio_j", "must be in [0, 1)");
  require(damping_mode_i >= 1 && damping_mode_i <= 3, "damping_mode_i", "must be in 1..3");
  require(damping_mode_j >= 1 && damping_mode_j <= 3, "damping_mode_j", "must be in 1..3");
  require(damping_mode_i != damping_mode_j, "damping_mode_j", "must differ from damping_mode_i");
  require(bents.size() >= 2, "bents", "at least 2 bents are needed (torsional stiffness)");
  bool distinct = false;
  for (std::size_t j = 0; j < bents.size(); ++j) {
    const std::string prefix = "bents[" + std::to_string(j) + "].";
    require(std::isfinite(bents[j].position), prefix + "position", "must be finite [m]");
    require(std::abs(bents[j].position) <= 0.5 * deck.length, prefix + "position",
            "must lie on the deck, |s| <= L/2 [m]");
    if (bents[j].position != bents[0].position) distinct = true;
    try {
      bents[j].longitudinal.validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(prefix + "longitudinal." + e.what());
    }
    try {
      bents[j].transverse.validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(prefix + "transverse." + e.what());
    }
  }
  require(distinct, "bents", "need at least 2 distinct positions (torsional stiffness)");
  require(initial_position.allFinite(), "initial_position", "must be finite [m, m, rad]");
  require(initial_velocity.allFinite(), "initial_velocity", "must be finite [m/s, m/s, rad/s]");
}

// ---------------------------------------------------------------------------------------------
// Bridge

Bridge::Bridge(const Parameters& p, Excitation excitation)
    : SystemBase({"x", "y", "theta"}, {"vx", "vy", "omega"}), p_(p),
      excitation_(std::move(excitation)) {
  p_.validate();
  const std::size_t nb = p_.bents.size();
  if (!excitation_.bents.empty() && excitation_.bents.size() != nb) {
    std::ostringstream s;
    s << "excitation.bents: " << excitation_.bents.size() << " motions for " << nb
      << " bents; give none or one per bent";
    throw std::invalid_argument(s.str());
  }
  integrators::Matrix mass = integrators::Matrix::Zero(3, 3);
  mass(0, 0) = mass(1, 1) = p_.mass;
  mass(2, 2) = p_.inertia;
  set_mass(mass);
  set_initial_state(p_.initial_position, p_.initial_velocity);

  for (const auto& b : p_.bents) {
    springs_x_.emplace_back(b.longitudinal);
    springs_y_.emplace_back(b.transverse);
    const Eigen::Vector3d by(0.0, 1.0, b.position);
    k0_(0, 0) += b.longitudinal.k0;
    k0_ += b.transverse.k0 * by * by.transpose();
  }
  const Eigen::LDLT<Eigen::Matrix3d> k0_ldlt(k0_);
  for (const auto& b : p_.bents) {
    qs_x_.push_back(k0_ldlt.solve(Eigen::Vector3d(b.longitudinal.k0, 0.0, 0.0)));
    qs_y_.push_back(k0_ldlt.solve(b.transverse.k0 * Eigen::Vector3d(0.0, 1.0, b.position)));
  }
  rayleigh_ = rayleigh(mass, integrators::Matrix(k0_), p_.damping_mode_i, p_.damping_ratio_i,
                       p_.damping_mode_j, p_.damping_ratio_j);
  c_ = rayleigh_.a0 * mass + rayleigh_.a1 * k0_;

  corners_ = p_.deck.corner_faces();
  faces_ = p_.deck.face_points();

  for (std::size_t j = 0; j < nb; ++j) {
    SupportIndex ix;
    if (!excitation_.bents.empty()) {
      ix.longitudinal = motion_index(excitation_.bents[j].longitudinal, false);
      ix.transverse = motion_index(excitation_.bents[j].transverse, false);
    }
    bent_index_.push_back(ix);
  }
  for (std::size_t a = 0; a < 2; ++a) {
    const auto& s = excitation_.seats[a];
    seat_index_[a] = {motion_index(s.longitudinal, true), motion_index(s.transverse, true),
                      motion_index(s.rotation, true)};
  }
  values_.assign(motions_.size(), MotionValue{});

  // Initial penetration at t0 = 0 with the seats at their initial pose.
  for (int i = 0; i < 4; ++i) {
    const auto k = corner_contact(corners_[static_cast<std::size_t>(i)], p_.initial_position,
                                  p_.initial_velocity,
                                  seat_motion(DeckGeometry::abutment_of(i), initial_time()));
    if (k.gap_normal < -kPenetrationTolerance) {
      std::ostringstream s;
      s << "initial_position: initial penetration at contact " << i + 1
        << " (g_N = " << k.gap_normal << " m); the initial gaps must be >= 0";
      throw std::invalid_argument(s.str());
    }
  }
}

int Bridge::motion_index(const Motion& m, bool needs_acceleration) {
  if (!m) return kNone;
  const auto it = std::find(motions_.begin(), motions_.end(), m.get());
  const auto i = static_cast<std::size_t>(it - motions_.begin());
  if (it == motions_.end()) {
    motions_.push_back(m.get());
    needs_acceleration_.push_back(0);
  }
  if (needs_acceleration) needs_acceleration_[i] = 1;
  return static_cast<int>(i);
}

void Bridge::update_motions(double t) const {
  if (t == values_t_) return;
  for (std::size_t i = 0; i < motions_.size(); ++i) {
    const GroundMotion::Values g = motions_[i]->values(t);
    MotionValue& v = values_[i];
    v.d = g.displacement;
    v.v = g.velocity;
    // The bents need no acceleration: only the seats' contact kinematics (wbar) use it.
    v.a = needs_acceleration_[i] ? g.acceleration : 0.0;
  }
  us_dot_ = Eigen::Vector3d::Zero();
  for (std::size_t j = 0; j < p_.bents.size(); ++j) {
    us_dot_ += qs_x_[j] * value(bent_index_[j].longitudinal).v +
               qs_y_[j] * value(bent_index_[j].transverse).v;
  }
  values_t_ = t;
}

PlanarMotion Bridge::seat_motion_cached(int seat) const {
  const auto a = static_cast<std::size_t>(seat);
  const SupportIndex& ix = seat_index_[a];
  const MotionValue &mx = value(ix.longitudinal), &my = value(ix.transverse),
                    &mr = value(ix.rotation);
  PlanarMotion m;
  m.position << faces_[a].x() + mx.d, faces_[a].y() + my.d, mr.d;
  m.velocity << mx.v, my.v, mr.v;
  m.acceleration << mx.a, my.a, mr.a;
  return m;
}

PlanarMotion Bridge::seat_motion(int seat, double t) const {
  update_motions(t);
  return seat_motion_cached(seat);
}

Eigen::Vector3d Bridge::quasi_static_velocity(double t) const {
  update_motions(t);
  return us_dot_;
}

void Bridge::forces(double t, const integrators::Vector& q, const integrators::Vector& u,
                    integrators::Vector& f) {
  update_motions(t);
  Eigen::Vector3d fs = Eigen::Vector3d::Zero();
  for (std::size_t j = 0; j < p_.bents.size(); ++j) {
    const double s = p_.bents[j].position;
    // Deck displacement at the bent relative to the bent's own ground (small rotations).
    const double dx = q(0) - value(bent_index_[j].longitudinal).d;
    const double dy = q(1) + s * q(2) - value(bent_index_[j].transverse).d;
    const double fx = springs_x_[j].set_trial(dx);
    const double fy = springs_y_[j].set_trial(dy);
    fs(0) -= fx;
    fs(1) -= fy;
    fs(2) -= s * fy;  // torque of the transverse bent force about the deck centre
  }
  const Eigen::Vector3d vr = u.head<3>() - us_dot_;
  f.head<3>() = fs - c_ * vr;
}

void Bridge::tangent(double, const integrators::Vector&, const integrators::Vector&,
                     integrators::Matrix& K, integrators::Matrix& C) {
  K.setZero(3, 3);
  for (std::size_t j = 0; j < p_.bents.size(); ++j) {
    const double s = p_.bents[j].position;
    const double kx = springs_x_[j].tangent(), ky = springs_y_[j].tangent();
    K(0, 0) += kx;
    K(1, 1) += ky;
    K(1, 2) += ky * s;
    K(2, 1) += ky * s;
    K(2, 2) += ky * s * s;
  }
  C = c_;
}

bool Bridge::tangent_changed() const {
  for (std::size_t j = 0; j < springs_x_.size(); ++j) {
    if (springs_x_[j].tangent_changed() || springs_y_[j].tangent_changed()) return true;
  }
  return false;
}

void Bridge::commit() {
  for (auto& s : springs_x_) s.commit();
  for (auto& s : springs_y_) s.commit();
}

void Bridge::revert() {
  for (auto& s : springs_x_) s.revert();
  for (auto& s : springs_y_) s.revert();
}

template <class Write>
void Bridge::each_corner(double t, const integrators::Vector& q, const integrators::Vector& u,
                         std::vector<integrators::ContactData>& out, Write write) const {
  if (out.size() != 4) out.resize(4);
  const Eigen::Vector3d q3 = q.head<3>(), u3 = u.head<3>();
  update_motions(t);
  const std::array<PlanarMotion, 2> seats{seat_motion_cached(0), seat_motion_cached(1)};
  for (std::size_t i = 0; i < 4; ++i) {
    const auto seat = static_cast<std::size_t>(DeckGeometry::abutment_of(static_cast<int>(i)));
    write(corners_[i], q3, u3, seats[seat], out[i]);
  }
}

void Bridge::contact_data(double t, const integrators::Vector& q, const integrators::Vector& u,
                          std::vector<integrators::ContactData>& out) const {
  each_corner(t, q, u, out,
              [this](const CornerFace& c, const Eigen::Vector3d& q3, const Eigen::Vector3d& u3,
                     const PlanarMotion& seat, integrators::ContactData& d) {
                copy_contact(corner_contact(c, q3, u3, seat), p_.restitution, p_.friction, d);
              });
}

void Bridge::contact_normals(double t, const integrators::Vector& q,
                             const integrators::Vector& u,
                             std::vector<integrators::ContactData>& out) const {
  each_corner(t, q, u, out,
              [](const CornerFace& c, const Eigen::Vector3d& q3, const Eigen::Vector3d& u3,
                 const PlanarMotion& seat, integrators::ContactData& d) {
                copy_contact_normal(corner_contact_normal(c, q3, u3, seat), d);
              });
}

integrators::PowerTerms Bridge::power(double t, const integrators::Vector&,
                                      const integrators::Vector& u) const {
  integrators::PowerTerms pw;
  update_motions(t);
  const Eigen::Vector3d us = us_dot_;
  const Eigen::Vector3d vr = u.head<3>() - us;
  const Eigen::Vector3d cvr = c_ * vr;
  pw.damping = vr.dot(cvr);
  double ground = -us.dot(cvr);
  for (std::size_t j = 0; j < p_.bents.size(); ++j) {
    ground -= springs_x_[j].force() * value(bent_index_[j].longitudinal).v +
              springs_y_[j].force() * value(bent_index_[j].transverse).v;
  }
  pw.ground = ground;
  return pw;
}

integrators::EnergyState Bridge::energy(double, const integrators::Vector&) const {
  integrators::EnergyState e;
  for (std::size_t j = 0; j < springs_x_.size(); ++j) {
    e.stored += springs_x_[j].stored_energy() + springs_y_[j].stored_energy();
    e.hysteretic += springs_x_[j].dissipated_energy() + springs_y_[j].dissipated_energy();
  }
  return e;
}

}  // namespace nsb::models
