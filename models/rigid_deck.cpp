#include "models/rigid_deck.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace nsb::models {

namespace {

void require(bool ok, const std::string& field, const std::string& what) {
  if (!ok) throw std::invalid_argument(field + ": " + what);
}

bool finite3(const Eigen::Vector3d& v) { return v.allFinite(); }

}  // namespace

void DeckGeometry::validate(const std::string& prefix) const {
  require(std::isfinite(length) && length > 0, prefix + "length", "must be > 0 [m]");
  require(std::isfinite(width) && width > 0, prefix + "width", "must be > 0 [m]");
  // Beyond 80 degrees the corners run off to infinity (tan alpha) and the model is meaningless.
  require(std::isfinite(skew_deg) && std::abs(skew_deg) < 80.0, prefix + "skew_deg",
          "must be in (-80, 80) [deg]");
  require(std::isfinite(gap_right) && gap_right >= 0, prefix + "gap_right", "must be >= 0 [m]");
  require(std::isfinite(gap_left) && gap_left >= 0, prefix + "gap_left", "must be >= 0 [m]");
}

std::array<Eigen::Vector2d, 2> DeckGeometry::face_points() const {
  return {Eigen::Vector2d(-0.5 * length - gap_left, 0.0),
          Eigen::Vector2d(0.5 * length + gap_right, 0.0)};
}

std::array<CornerFace, 4> DeckGeometry::corner_faces() const {
  const double alpha = skew_deg * std::numbers::pi / 180.0;
  const double ta = std::tan(alpha), ca = std::cos(alpha), sa = std::sin(alpha);
  const double hl = 0.5 * length, hw = 0.5 * width;
  // Face normals from each abutment towards the deck: the faces run along (sin a, cos a).
  const Eigen::Vector2d n_left(ca, -sa), n_right(-ca, sa);
  std::array<CornerFace, 4> c;
  c[0].body_point = {-hl + hw * ta, hw};   // 1: left end, y_b = +W/2
  c[1].body_point = {-hl - hw * ta, -hw};  // 2: left end, y_b = -W/2
  c[2].body_point = {hl + hw * ta, hw};    // 3: right end, y_b = +W/2
  c[3].body_point = {hl - hw * ta, -hw};   // 4: right end, y_b = -W/2
  for (int i = 0; i < 4; ++i) {
    c[static_cast<std::size_t>(i)].face_point = Eigen::Vector2d::Zero();  // abutment-frame origin
    c[static_cast<std::size_t>(i)].face_normal = abutment_of(i) == 0 ? n_left : n_right;
  }
  return c;
}

void RigidDeck::Parameters::validate() const {
  require(std::isfinite(mass) && mass > 0, "mass", "must be > 0 [t]");
  require(std::isfinite(inertia) && inertia > 0, "inertia", "must be > 0 [t m^2]");
  geometry().validate();
  require(std::isfinite(restitution) && restitution >= 0 && restitution <= 1, "restitution",
          "must be in [0, 1]");
  require(std::isfinite(friction) && friction >= 0, "friction", "must be >= 0");
  require(finite3(initial_position), "initial_position", "must be finite [m, m, rad]");
  require(finite3(initial_velocity), "initial_velocity", "must be finite [m/s, m/s, rad/s]");
  const auto corners = geometry().corner_faces();
  const auto faces = geometry().face_points();
  for (int i = 0; i < 4; ++i) {
    PlanarMotion m;
    m.position.head<2>() = faces[static_cast<std::size_t>(DeckGeometry::abutment_of(i))];
    const auto k = corner_contact(corners[static_cast<std::size_t>(i)], initial_position,
                                  Eigen::Vector3d::Zero(), m);
    if (k.gap_normal < -kPenetrationTolerance) {
      std::ostringstream s;
      s << "initial penetration at contact " << i + 1 << " (g_N = " << k.gap_normal
        << " m); the initial gaps must be >= 0";
      throw std::invalid_argument("initial_position: " + s.str());
    }
  }
}

RigidDeck::RigidDeck(const Parameters& p) : p_(p) {
  p_.validate();
  corners_ = p_.geometry().corner_faces();
  const auto faces = p_.geometry().face_points();
  for (int a = 0; a < 2; ++a) {
    abutments_[static_cast<std::size_t>(a)].position.head<2>() = faces[static_cast<std::size_t>(a)];
  }
  mass_ = integrators::Matrix::Zero(3, 3);
  mass_(0, 0) = mass_(1, 1) = p_.mass;
  mass_(2, 2) = p_.inertia;
}

void RigidDeck::forces(double, const integrators::Vector&, const integrators::Vector&,
                       integrators::Vector& f) {
  f.setZero();  // no piers, no gravity in the plane
}

void RigidDeck::tangent(double, const integrators::Vector&, const integrators::Vector&,
                        integrators::Matrix& K, integrators::Matrix& C) {
  K.setZero(3, 3);
  C.setZero(3, 3);
}

void copy_contact(const ContactKinematics& k, double restitution, double friction,
                  integrators::ContactData& out) {
  out.gap_normal = k.gap_normal;
  out.w_normal = k.w_normal;
  out.w_tangent = k.w_tangent;
  out.what_normal = k.what_normal;
  out.what_tangent = k.what_tangent;
  out.wbar_normal = k.wbar_normal;
  out.wbar_tangent = k.wbar_tangent;
  out.restitution = restitution;
  out.friction = friction;
  out.far = k.gap_normal > kFarGap + kFarHorizon * std::max(0.0, -k.gap_rate_normal);
}

void RigidDeck::contact_data(double, const integrators::Vector& q, const integrators::Vector& u,
                             std::vector<integrators::ContactData>& out) const {
  if (out.size() != 4) out.resize(4);
  const Eigen::Vector3d q3 = q.head<3>(), u3 = u.head<3>();
  for (std::size_t i = 0; i < 4; ++i) {
    const auto k = corner_contact(corners_[i], q3, u3,
                                  abutments_[static_cast<std::size_t>(DeckGeometry::abutment_of(
                                      static_cast<int>(i)))]);
    copy_contact(k, p_.restitution, p_.friction, out[i]);
  }
}

integrators::PowerTerms RigidDeck::power(double, const integrators::Vector&,
                                         const integrators::Vector&) const {
  return {};  // no damping, fixed abutments, no applied loads
}

integrators::EnergyState RigidDeck::energy(double, const integrators::Vector&) const {
  return {};  // no springs, no gravity in the plane
}

}  // namespace nsb::models
