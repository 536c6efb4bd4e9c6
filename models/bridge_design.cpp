#include "models/bridge_design.hpp"
#include "models/field_checks.hpp"

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
// BridgeDesign

BridgeDesign BridgeDesign::benchmark() {
  BridgeDesign p;
  const double span = 0.25 * p.deck.length;  // four equal spans (assumed, docs/bridge.md)
  const double positions[3] = {-span, 0.0, span};
  const double heights[3] = {1.83, 2.44, 1.52};    // assumed, docs/bridge.md
  for (int j = 0; j < 3; ++j) {
    BentDesign d;
    d.height = heights[j];
    p.bents.push_back({.position = positions[j], .longitudinal = d.takeda(),
                       .transverse = d.takeda()});
  }
  return p;
}

BridgeDesign BridgeDesign::free_deck() {
  BridgeDesign p;
  p.mass = 0.0;
  p.inertia = 0.0;
  p.deck = DeckGeometry{};
  p.restitution = 0.0;
  p.friction = 0.0;
  return p;
}

namespace {

void validate_bents(const std::vector<BridgeDesign::Bent>& bents, double length) {
  if (bents.empty()) return;  // a free deck
  require(bents.size() >= 2, "bents", "none (a free deck), or at least 2 (torsional stiffness)");
  bool distinct = false;
  for (std::size_t j = 0; j < bents.size(); ++j) {
    const std::string prefix = indexed("bents", j);
    require(std::isfinite(bents[j].position), prefix + "position", "must be finite [m]");
    require(std::abs(bents[j].position) <= 0.5 * length, prefix + "position",
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
}

}  // namespace

void BridgeDesign::validate() const {
  require(finite_positive(mass), "mass", "must be > 0 [t]");
  require(finite_positive(inertia), "inertia", "must be > 0 [t m^2]");
  deck.validate();
  require(std::isfinite(restitution) && restitution >= 0 && restitution <= 1, "restitution",
          "must be in [0, 1]");
  require(std::isfinite(friction) && friction >= 0, "friction", "must be >= 0");
  require(std::isfinite(compliance_stiffness) && compliance_stiffness >= 0,
          "compliance_stiffness", "must be >= 0 [kN/m^1.5] (0: solver.contact_stiffness)");
  require(std::isfinite(damping_ratio_i) && damping_ratio_i >= 0 && damping_ratio_i < 1,
          "damping_ratio_i", "must be in [0, 1)");
  require(std::isfinite(damping_ratio_j) && damping_ratio_j >= 0 && damping_ratio_j < 1,
          "damping_ratio_j", "must be in [0, 1)");
  require(damping_mode_i >= 1 && damping_mode_i <= 3, "damping_mode_i", "must be in 1..3");
  require(damping_mode_j >= 1 && damping_mode_j <= 3, "damping_mode_j", "must be in 1..3");
  require(damping_mode_i != damping_mode_j, "damping_mode_j", "must differ from damping_mode_i");
  validate_bents(bents, deck.length);
  require(initial_position.allFinite(), "initial_position", "must be finite [m, m, rad]");
  require(initial_velocity.allFinite(), "initial_velocity", "must be finite [m/s, m/s, rad/s]");
  if (!excitation.bents.empty() && excitation.bents.size() != bents.size()) {
    std::ostringstream s;
    s << excitation.bents.size() << " motions for " << bents.size()
      << " bents; give none or one per bent";
    require(false, "excitation.bents", s.str());
  }
  // Initial penetration with the seats at rest.
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
      require(false, "initial_position", s.str());
    }
  }
}

PlanarMotion BridgeDesign::seat_motion(int seat, double t) const {
  const auto a = static_cast<std::size_t>(seat);
  const SupportMotion& s = excitation.seats.at(a);
  const auto value = [t](const parts::Motion& m) {
    return m ? m->values(t) : GroundMotion::Values{};
  };
  const GroundMotion::Values x = value(s.longitudinal), y = value(s.transverse),
                             r = value(s.rotation);
  const Eigen::Vector2d face = deck.face_points()[a];
  PlanarMotion m;
  m.position << face.x() + x.displacement, face.y() + y.displacement, r.displacement;
  m.velocity << x.velocity, y.velocity, r.velocity;
  m.acceleration << x.acceleration, y.acceleration, r.acceleration;
  return m;
}

}  // namespace nsb::models
