#include "models/deck_chain.hpp"
#include "models/field_checks.hpp"

#include "models/deck_geometry.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace nsb::models {

namespace {

parts::RigidBody body(const DeckChain::Parameters& p, std::size_t i) {
  const auto& d = p.decks[i];
  const Eigen::Vector3d rest(DeckChain::rest_position(p, static_cast<int>(i)), 0.0, 0.0);
  return {.mass = d.mass, .inertia = d.inertia, .length = d.length,
          .width = d.width > 0.0 ? d.width : p.width,
          .skew_deg = p.skew_deg, .initial_position = rest + d.initial_displacement,
          .initial_velocity = d.initial_velocity};
}

}  // namespace

void DeckChain::Parameters::validate() const {
  require(!decks.empty(), "decks", "at least one deck is needed");
  require(joints.size() == decks.size() + 1, "joints",
          "one per deck plus one (left abutment, hinges, right abutment)");
  require(std::isfinite(width) && width > 0, "width", "must be > 0 [m]");
  require(std::isfinite(skew_deg) && std::abs(skew_deg) < 80.0, "skew_deg",
          "must be in (-80, 80) [deg]");
  for (std::size_t i = 0; i < decks.size(); ++i) {
    const std::string prefix = indexed("decks", i);
    const auto& d = decks[i];
    require(std::isfinite(d.mass) && d.mass > 0, prefix + "mass", "must be > 0 [t]");
    require(std::isfinite(d.inertia) && d.inertia > 0, prefix + "inertia",
            "must be > 0 [t m^2]");
    require(std::isfinite(d.length) && d.length > 0, prefix + "length", "must be > 0 [m]");
    require(std::isfinite(d.width) && d.width >= 0, prefix + "width",
            "must be >= 0 [m] (0: the chain's width)");
    require(d.initial_displacement.allFinite(), prefix + "initial_displacement",
            "must be finite [m, m, rad]");
    require(d.initial_velocity.allFinite(), prefix + "initial_velocity",
            "must be finite [m/s, m/s, rad/s]");
  }
  for (std::size_t k = 0; k < joints.size(); ++k) {
    const std::string prefix = indexed("joints", k);
    const auto& j = joints[k];
    require(std::isfinite(j.gap) && j.gap >= 0, prefix + "gap", "must be >= 0 [m]");
    require(std::isfinite(j.restitution) && j.restitution >= 0 && j.restitution <= 1,
            prefix + "restitution", "must be in [0, 1]");
    require(std::isfinite(j.friction) && j.friction >= 0, prefix + "friction", "must be >= 0");
  }
}

double DeckChain::rest_position(const Parameters& p, int deck) {
  double x = 0.0;  // the left abutment face
  for (int k = 0; k <= deck; ++k) {
    const auto i = static_cast<std::size_t>(k);
    x += p.joints[i].gap + (k == 0 ? 0.0 : p.decks[i - 1].length);
  }
  return x + 0.5 * p.decks[static_cast<std::size_t>(deck)].length;
}

Assembly::Parts DeckChain::parts(const Parameters& p) {
  p.validate();
  const std::size_t n = p.decks.size();
  Assembly::Parts out;
  for (std::size_t i = 0; i < n; ++i) out.bodies.push_back(body(p, i));
  // The abutments: fixed faces through (0, 0) and through the right end of the chain.
  const double right = rest_position(p, static_cast<int>(n - 1)) + 0.5 * p.decks[n - 1].length +
                       p.joints[n].gap;
  out.prescribed.resize(2);  // no motion
  out.prescribed[1].reference = Eigen::Vector2d(right, 0.0);
  // Abutment face normals, from the abutment towards the deck (models/deck_geometry.hpp).
  const DeckGeometry plan{.length = 1.0, .width = p.width, .skew_deg = p.skew_deg};
  const parts::Face left_face{.point = Eigen::Vector2d::Zero(), .normal = plan.face_normal(0)};
  const parts::Face right_face{.point = Eigen::Vector2d::Zero(), .normal = plan.face_normal(2)};
  // The outputs' family and name of each contact: its joint and the corner's side.
  auto add = [&](int deck, int corner, parts::Obstacle obstacle, int index,
                 const parts::Face& face, const Joint& j, const std::string& family,
                 const std::string& joint, const parts::Face* partner_face = nullptr) {
    out.contacts.push_back({.body = deck, .corner = corner, .obstacle = obstacle,
                            .obstacle_index = index, .face = face,
                            .restitution = j.restitution, .friction = j.friction,
                            .stiffness = j.compliance_stiffness,
                            .family = family,
                            .name = joint + (corner % 2 == 0 ? " +W/2" : " -W/2"),
                            .partner_corner = partner_face != nullptr ? corner + 2 : -1,
                            .partner_face = partner_face != nullptr ? *partner_face
                                                                    : parts::Face{}});
  };
  for (int corner : {0, 1}) {
    add(0, corner, parts::Obstacle::kPrescribed, 0, left_face, p.joints[0], "abutment", "left");
  }
  for (std::size_t k = 1; k < n; ++k) {
    // Each side of the hinge: deck k's left corner on deck k - 1's right end face, or deck
    // k - 1's right corner (2, 3) on deck k's left end face (parts::CornerContact).
    const parts::Face face = parts::bounded_end_face(out.bodies[k - 1], parts::End::kRight);
    const parts::Face partner = parts::bounded_end_face(out.bodies[k], parts::End::kLeft);
    for (int corner : {0, 1}) {
      add(static_cast<int>(k), corner, parts::Obstacle::kBody, static_cast<int>(k - 1), face,
          p.joints[k], "hinge", "hinge " + std::to_string(k), &partner);
    }
  }
  for (int corner : {2, 3}) {
    add(static_cast<int>(n - 1), corner, parts::Obstacle::kPrescribed, 1, right_face,
        p.joints[n], "abutment", "right");
  }
  return out;
}

std::span<const config::Field<DeckChain::Joint>> joint_fields() {
  namespace c = config;
  using P = DeckChain::Joint;
  static const c::Field<P> f[] = {
      c::number<&P::gap>("gap", "m", c::non_negative(),
                         "clear distance along the axis between the two faces at rest"),
      c::number<&P::restitution>("restitution", "-", c::closed(0, 1),
                                 "Newton's ε_N of the joint's two corner contacts"),
      c::number<&P::friction>("friction", "-", c::non_negative(),
                              "Coulomb's μ of the joint's two corner contacts"),
      c::number<&P::compliance_stiffness>("compliance_stiffness", "kN/m^1.5", c::non_negative(),
                                          "Hertz k of eq. (9) for the joint's two contacts "
                                          "under the compliance method; 0: the default, "
                                          "solver.contact_stiffness scaled to the colliding "
                                          "mass (solver.reference_mass)"),
  };
  return f;
}

}  // namespace nsb::models
