// A free planar rigid deck (parallelogram) between two abutments, without piers and without
// gravity in the plane: the deck model of the rotation criterion (eq. 1) and of the impact
// law (eq. 3-7) of Shi & Dimitrakopoulos (2017).
//
// Geometry, contact numbering and gaps: models/deck_geometry.hpp (the paper's contacts 1..4
// are indices 0..3 there). W_N opens the gap; the tangent is the face normal n (from the abutment
// towards the deck) rotated +90 degrees.
//
// Units: kN, t, m, s, rad.
#pragma once

#include "config/schema.hpp"
#include "integrators/system.hpp"
#include "models/contact_geometry.hpp"
#include "models/deck_geometry.hpp"

#include <span>
#include <array>
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

class RigidDeck final : public integrators::SystemBase {
 public:
  struct Parameters {
    double mass = 0;         // m [t], > 0
    double inertia = 0;      // I about the centre [t m^2], > 0
    DeckGeometry deck;       // L, W, alpha and the two gaps (models/deck_geometry.hpp)
    double restitution = 0;  // eps_N in [0, 1], all four contacts
    double friction = 0;     // mu >= 0, all four contacts
    Eigen::Vector3d initial_position = Eigen::Vector3d::Zero(),  // (x, y, theta) [m, m, rad]
        initial_velocity = Eigen::Vector3d::Zero();              // (vx, vy, omega)
    // Throws std::invalid_argument naming the field; also rejects an initial penetration.
    void validate() const;
  };
  explicit RigidDeck(const Parameters&);

  const Parameters& parameters() const { return p_; }

  // No piers, no gravity in the plane, fixed abutments: no smooth force, no stored energy and
  // no energy flow (SystemBase's defaults); only the four contacts.
  int contacts() const override { return 4; }
  void contact_data(double t, const integrators::Vector& q, const integrators::Vector& u,
                    std::vector<integrators::ContactData>& out) const override;

 private:
  Parameters p_;
  std::array<CornerFace, 4> corners_;
  std::array<PlanarMotion, 2> abutments_;  // fixed poses
};

// Writes one ContactKinematics into a ContactData (sizes already 3).
void copy_contact(const ContactKinematics& k, double restitution, double friction,
                  integrators::ContactData& out);
// Writes the normal part (System::contact_normals) into a ContactData: gap_normal, w_normal,
// what_normal and far, as copy_contact() does.
void copy_contact_normal(const ContactNormal& k, integrators::ContactData& out);

// The [model] keys of kind = "rigid_deck" besides kind (docs/scenes.md).
std::span<const config::Field<RigidDeck::Parameters>> rigid_deck_fields();

}  // namespace nsb::models
