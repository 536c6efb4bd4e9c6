// The design of a bridge of one rigid deck between two abutment seats: what a scene says about
// it and what the figures, claims, benchmarks and checks read from it (deck size, mass,
// inertia, gaps, contact law, damping, bents, support motions). models/bridge_parts.hpp builds
// it as an assembly of parts (models/assembly.hpp), the one bridge model.
//
// The benchmark bridge of Shi & Dimitrakopoulos (2017) is one such design
// (BridgeDesign::benchmark()): a rigid deck (x, y, theta) on three two-column RC bents with
// Takeda hysteresis, Rayleigh damping, and four frictional deck-corner contacts against two
// abutment seats whose motion is prescribed. Multi-support excitation: every bent and every
// seat has its own ground motion (eq. 2). A design without bents is the free rigid deck of the
// rotation criterion (eq. 1) and of the impact law (eqs. 3-7): no piers, no damping, no
// gravity in the plane; only the four contacts.
//
// Units: kN, t, m, s, rad.
#pragma once

#include "models/contact_geometry.hpp"
#include "models/deck_geometry.hpp"
#include "models/parts.hpp"
#include "models/takeda.hpp"

#include <Eigen/Dense>

#include <array>
#include <string>
#include <vector>

namespace nsb::models {

// A bent of identical circular RC columns, fixed at both ends, and the engineering estimates
// of its springs (docs/bridge.md): per column k = 12 EI_eff / H^3 with EI_eff = cracked_ratio
// E pi d^4 / 64; yield displacement Delta_y = phi_y H^2 / 6 with phi_y = 2.25 eps_y / d
// (Priestley, Seible & Calvi 1996); yield force = bent stiffness * Delta_y. The same springs
// serve both directions.
struct BentDesign {
  double height = 0.0;               // clear column height H [m], > 0
  double column_diameter = 0.305;    // d [m], > 0
  int columns = 2;                   // columns per bent, >= 1
  double elastic_modulus = 3.0e7;    // E_c [kPa], > 0 (30 GPa)
  double cracked_ratio = 0.5;        // EI_eff / EI_gross, in (0, 1]
  double yield_strain = 0.0023;      // eps_y of the reinforcement [-], > 0
  double post_yield_ratio = 0.05;    // Takeda post-yield / yield stiffness, in [0, 1)
  double unloading_exponent = 0.4;   // Takeda alpha, in [0, 1]
  void validate(const std::string& prefix = "") const;  // throws naming the field
  double column_stiffness() const;     // [kN/m]
  double stiffness() const;            // columns * column_stiffness() [kN/m]
  double yield_displacement() const;   // [m]
  double yield_force() const;          // [kN]
  takeda::Parameters takeda() const;   // bilinear Takeda of the whole bent
};

struct BridgeDesign {
  // A bent under the deck: two Takeda springs at the position s along the deck axis, or its
  // columns at their offsets. Its transverse force acts with the lever arm s, each column's
  // longitudinal force with its offset (models/parts.hpp, Bent).
  struct Bent {
    double position = 0.0;                // s_j along the deck axis from the centre [m]
    takeda::Parameters longitudinal;      // bent spring along x (all columns together)
    takeda::Parameters transverse;        // bent spring along y
    // The columns' transverse positions from the deck axis [m] (one per column, each column
    // carrying 1/n of both springs at its own position); empty: the whole bent on the axis.
    std::vector<double> column_offsets{};
    double skew_deg = 0.0;                // the bent's own skew beta [deg] (parts.hpp, Bent)
  };
  // The ground motion of one support; null means none in that direction.
  struct SupportMotion {
    parts::Motion longitudinal;  // along global x [m]
    parts::Motion transverse;    // along global y [m]
    parts::Motion rotation;      // seats only: rotation about the face point; the record's
                                 // "acceleration" is the angular acceleration [rad/s^2]
  };
  struct Excitation {
    std::vector<SupportMotion> bents;    // empty, or one per bent
    std::array<SupportMotion, 2> seats;  // 0 = left, 1 = right
  };

  double mass = 140.5;        // m_d [t], > 0 (paper, sec. 3)
  double inertia = 13090.0;   // I_d [t m^2], > 0 (paper, sec. 3)
  // L = 110 ft = 33.53 m (Saiidi, Vosooghi & Nelson 2013); W, gaps assumed (docs/bridge.md).
  DeckGeometry deck{33.53, 2.44, 0.0, 0.0127, 0.0127};
  double restitution = 0.0;   // eps_N in [0, 1] (paper: 0)
  double friction = 0.5;      // mu >= 0 (paper: 0.5)
  double compliance_stiffness = 0.0;  // Hertz k of the four abutment contacts under the
                                      //   compliance method [kN/m^1.5], >= 0; 0: the run's
                                      //   default scaled to the colliding mass
                                      //   (integrators::contact_stiffness)
  double damping_ratio_i = 0.08, damping_ratio_j = 0.08;  // Rayleigh ratios, >= 0 (paper 8 %)
  int damping_mode_i = 1, damping_mode_j = 3;            // 1-based modes, distinct, in 1..3
  // None: a free deck (no damping, which needs the bents' stiffness); else >= 2 bents at >= 2
  // distinct positions (torsional stiffness).
  std::vector<Bent> bents;
  Eigen::Vector3d initial_position = Eigen::Vector3d::Zero();  // absolute (x, y, theta)
  Eigen::Vector3d initial_velocity = Eigen::Vector3d::Zero();
  Excitation excitation;      // no motion: fixed supports

  // Throws std::invalid_argument naming the field: a bad value, a bent excitation of the
  // wrong size, or an initial penetration with the seats at rest ("initial_position: ...").
  void validate() const;
  // The benchmark's design (docs/bridge.md): three bents of heights 1.83, 2.44, 1.52 m at
  // -L/4, 0, +L/4 (four equal spans), designed by BentDesign; no excitation.
  static BridgeDesign benchmark();
  // A free deck without size, mass or contact law (every value 0, no bents): the start of a
  // rigid_deck scene, which gives mass, inertia, length and width.
  static BridgeDesign free_deck();
  // Pose of seat a (0 left, 1 right) at time t, with derivatives: its reference face point
  // plus its displacement, rotated about that point (as the assembly poses the seat).
  PlanarMotion seat_motion(int seat, double t) const;
};

}  // namespace nsb::models
