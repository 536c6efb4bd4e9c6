// The restrainers and ground links of an assembly (models/parts.hpp): their states, forces,
// tangent, support power and energies, summed into models::Assembly's. Vectors of concrete
// types sized at construction: no allocation and no virtual call per part and step.
//
// Energy bookkeeping (the balance of integrators/system.hpp): a connector of force F along
// its elongation d stores and dissipates at the rate F d_dot (connectors::Cable, Law); the
// part of d_dot due to a support's motion is the work rate put in by the ground:
// -F_x u_gx_dot - F_y u_gy_dot for a ground link (as a bent), -F e . v_b for a restrainer
// anchored on a prescribed body (v_b its anchor's velocity); a restrainer between two free
// bodies puts no work in.
//
// Units: kN, t, m, s, rad.
#pragma once

#include "integrators/system.hpp"
#include "models/connectors.hpp"
#include "models/contact_geometry.hpp"
#include "models/parts.hpp"

#include <Eigen/Dense>

#include <vector>

namespace nsb::models {

class ConnectorSet {
 public:
  ConnectorSet() = default;
  // Throws std::invalid_argument naming "restrainers[i].field" or "links[i].field".
  // Registers the links' ground motions in `motions`.
  ConnectorSet(const std::vector<parts::RigidBody>& bodies,
               const std::vector<parts::PrescribedBody>& prescribed,
               const std::vector<parts::Restrainer>& restrainers,
               const std::vector<parts::GroundLink>& links, parts::MotionTable& motions);

  bool empty() const { return cables_.empty() && links_.empty(); }
  // K0 += the links' initial stiffness on body b (block at b's DOFs).
  void add_initial_stiffness(int body, Eigen::Matrix3d& k0) const;
  // The links' columns of the quasi-static support motion of body b, K0_bb^-1 k0 b.
  void set_quasi_static(int body, const Eigen::LDLT<Eigen::Matrix3d>& k0_bb);
  // us_dot of body b += the links' share at the motions' current values.
  void add_support_velocity(int body, const parts::MotionTable& motions,
                            Eigen::Vector3d& us) const;
  // f -= connector forces at (q, u), with the seats' poses `seats` (trial states set).
  void forces(const integrators::Vector& q, const parts::MotionTable& motions,
              const std::vector<PlanarMotion>& seats, integrators::Vector& f);
  // The same with every law on its committed branch (force_on_committed_branch), trial
  // states left as they are (integrators::System::forces_on_committed_branches).
  void forces_on_committed_branches(const integrators::Vector& q,
                                    const parts::MotionTable& motions,
                                    const std::vector<PlanarMotion>& seats,
                                    integrators::Vector& f);
  // K += the tangent of the last forces() call (the geometric stiffness of the cables'
  // direction change is left out: F / L0 is small against k).
  void tangent(integrators::Matrix& K) const;
  bool tangent_changed() const;
  void commit();
  void revert();
  // Work rate put in by the supports (see above), at the last forces() state.
  double ground_power(const parts::MotionTable& motions,
                      const std::vector<PlanarMotion>& seats) const;
  void energy(integrators::EnergyState& e) const;

 private:
  struct CableState {
    int offset_a = 0, offset_b = -1;  // offset_b < 0: anchored on prescribed body `seat`
    int seat = 0;
    Eigen::Vector3d rest_a = Eigen::Vector3d::Zero(), rest_b = Eigen::Vector3d::Zero();
    Eigen::Vector2d anchor_a = Eigen::Vector2d::Zero(), anchor_b = Eigen::Vector2d::Zero();
    double rest_length = 0.0;
    connectors::Cable cable;
    // From the last forces(): the columns j_a, j_b (F acts as -F j_a, +F j_b) and anchor
    // b from its body's origin in the global frame.
    Eigen::Vector3d j_a = Eigen::Vector3d::Zero(), j_b = Eigen::Vector3d::Zero();
    Eigen::Vector2d r_b = Eigen::Vector2d::Zero();
  };
  struct LinkState {
    int body = 0, offset = 0;
    double position = 0.0;
    connectors::Law x, y;
    int ground_x = parts::MotionTable::kNone, ground_y = parts::MotionTable::kNone;
    Eigen::Vector3d qs_x = Eigen::Vector3d::Zero(), qs_y = Eigen::Vector3d::Zero();
  };
  // kCommittedBranch: the cable's tension on its committed branch, its trial left as it is.
  template <bool kCommittedBranch>
  void cable_force(CableState& c, const integrators::Vector& q,
                   const std::vector<PlanarMotion>& seats, integrators::Vector& f) const;
  template <bool kCommittedBranch>
  void forces_of(const integrators::Vector& q, const parts::MotionTable& motions,
                 const std::vector<PlanarMotion>& seats, integrators::Vector& f);

  std::vector<CableState> cables_;
  std::vector<LinkState> links_;
};

}  // namespace nsb::models
