#include "models/rigid_deck.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace nsb::models {

void RigidDeck::Parameters::validate() const {
  // Every field's range, as the scene schema declares it; then what no single field says.
  config::validate_fields<Parameters>(*this, rigid_deck_fields());
  const auto corners = deck.corner_faces();
  const auto faces = deck.face_points();
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

RigidDeck::RigidDeck(const Parameters& p)
    : SystemBase({"x", "y", "theta"}, {"vx", "vy", "omega"}), p_(p) {
  p_.validate();
  corners_ = p_.deck.corner_faces();
  const auto faces = p_.deck.face_points();
  for (int a = 0; a < 2; ++a) {
    abutments_[static_cast<std::size_t>(a)].position.head<2>() = faces[static_cast<std::size_t>(a)];
  }
  integrators::Matrix mass = integrators::Matrix::Zero(3, 3);
  mass(0, 0) = mass(1, 1) = p_.mass;
  mass(2, 2) = p_.inertia;
  set_mass(std::move(mass));
  set_initial_state(p_.initial_position, p_.initial_velocity);
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

void copy_contact_normal(const ContactNormal& k, integrators::ContactData& out) {
  out.gap_normal = k.gap_normal;
  out.w_normal = k.w_normal;
  out.what_normal = k.what_normal;
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

std::span<const config::Field<RigidDeck::Parameters>> rigid_deck_fields() {
  namespace c = config;
  using P = RigidDeck::Parameters;
  using D = DeckGeometry;
  static const c::Field<P> f[] = {
      c::number<&P::mass>("mass", "t", c::positive(), "deck mass (required)"),
      c::number<&P::inertia>("inertia", "t m^2", c::positive(),
                             "rotational inertia about the centre (required)"),
      c::number<&P::deck, &D::length>("length", "m", c::positive(), "L, along the axis (required)"),
      c::number<&P::deck, &D::width>("width", "m", c::positive(), "W (required)"),
      c::number<&P::deck, &D::skew_deg>("skew_deg", "deg", c::open(-80, 80), "skew angle α"),
      c::number<&P::deck, &D::gap_right>("gap_right", "m", c::non_negative(),
                                         "clear distance along the axis at x = y = θ = 0"),
      c::number<&P::deck, &D::gap_left>("gap_left", "m", c::non_negative(),
                                        "clear distance along the axis at x = y = θ = 0"),
      c::number<&P::restitution>("restitution", "-", c::closed(0, 1), "all four contacts"),
      c::number<&P::friction>("friction", "-", c::non_negative(), "all four contacts"),
      c::vector3<&P::initial_position>("initial_position", "m, m, rad",
                                       "(x, y, θ); no corner may penetrate"),
      c::vector3<&P::initial_velocity>("initial_velocity", "m/s, m/s, rad/s", "(vx, vy, ω)"),
  };
  return f;
}

}  // namespace nsb::models
