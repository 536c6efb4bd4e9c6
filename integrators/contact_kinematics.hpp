// Contact kinematics over an index set: the contact velocities and the Delassus matrix of
// eqs. (3), (7) and (8) of Shi & Dimitrakopoulos (2017).
//
// For the contacts i of an index set, with normal and tangential columns W_N,i, W_T,i and the
// rheonomic parts what_N,i, what_T,i of ContactData (integrators/system.hpp):
//
//   gdot_N = W_N^T u + what_N,     gdot_T = W_T^T u + what_T                           (3), (7)
//   gdot+  = G Lambda + gdot_free,  G = W^T A^-1 B,  gdot_free = W^T u_free + what    (8)
//
// A^-1 is M^-1 for an impact and the iteration matrix inverse of a Moreau–Jean step. B = W
// except at acceleration level for a sliding contact, whose friction force
// lambda_T = -mu s lambda_N enters its normal column: B_N,i = W_N,i - mu_i s_i W_T,i
// (Pfeiffer & Glocker 1996, ch. 6). At acceleration level accelerations replace velocities
// and the rheonomic parts are wbar_N, wbar_T.
//
// The columns are ordered normals first, then (when the problem has tangential unknowns)
// tangents, as lcp::FrictionalProblem expects. Every buffer is sized at construction for the
// largest index set: nothing is allocated per call.
#pragma once

#include "integrators/system.hpp"

#include <vector>

namespace nsb::integrators {

// The level at which a contact problem is posed.
enum class ContactLevel {
  kVelocity,      // impulses and velocities (Moreau–Jean, impacts): rheonomic part what
  kAcceleration,  // forces and accelerations (event-driven smooth phases): rheonomic part wbar
};

class ContactKinematics {
 public:
  ContactKinematics() = default;
  ContactKinematics(int dofs, int max_contacts);

  // Gathers the columns of the index set `index` (indices into `contacts`): k normals, then
  // k tangents when `tangential`. slip_coupling, when not null, holds per index-set entry the
  // factor c_j of B_N,j = W_N,j + c_j W_T,j (c_j = -mu_j s_j for a sliding contact at
  // acceleration level, else 0).
  void gather(const std::vector<ContactData>& contacts, const std::vector<int>& index,
              bool tangential, const double* slip_coupling = nullptr);
  // G = W^T A^-1 B (eq. 8), written into g (size() x size()); keeps A^-1 B for apply().
  void delassus(const Matrix& a_inv, Eigen::Ref<Matrix> g);
  // W^T v + (what or wbar) (eqs. 3 and 7) for the gathered index set, into out (size()).
  void velocities(const std::vector<ContactData>& contacts, const std::vector<int>& index,
                  const Vector& v, ContactLevel level, Eigen::Ref<Vector> out) const;
  // v += A^-1 B Lambda: the velocity (or acceleration) change the impulses (forces) cause.
  void apply(const Eigen::Ref<const Vector>& lambda, Vector& v) const;

  int contacts() const { return k_; }  // k, the size of the index set
  int size() const { return size_; }   // k, or 2k with tangential columns
  bool tangential() const { return size_ > k_; }

 private:
  int n_ = 0;
  int k_ = 0;
  int size_ = 0;
  Matrix w_;        // [W_N | W_T] of the index set, n x 2 max_contacts
  Matrix b_;        // B: W with the sliding contacts' friction folded into their normals
  Matrix a_inv_b_;  // A^-1 B
  bool coupled_ = false;  // B differs from W
};

}  // namespace nsb::integrators
