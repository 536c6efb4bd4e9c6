#include "integrators/contact_kinematics.hpp"

namespace nsb::integrators {

ContactKinematics::ContactKinematics(int dofs, int max_contacts)
    : n_(dofs),
      w_(Matrix::Zero(dofs, 2 * max_contacts)),
      b_(Matrix::Zero(dofs, 2 * max_contacts)),
      a_inv_b_(Matrix::Zero(dofs, 2 * max_contacts)) {}

void ContactKinematics::gather(const std::vector<ContactData>& contacts,
                               const std::vector<int>& index, bool tangential,
                               const double* slip_coupling) {
  k_ = static_cast<int>(index.size());
  size_ = tangential ? 2 * k_ : k_;
  coupled_ = false;
  for (int j = 0; j < k_; ++j) {
    const ContactData& c = contacts[static_cast<std::size_t>(index[static_cast<std::size_t>(j)])];
    w_.col(j) = c.w_normal;
    if (tangential) w_.col(k_ + j) = c.w_tangent;
    if (slip_coupling != nullptr && slip_coupling[j] != 0.0) coupled_ = true;
  }
  if (!coupled_) return;
  b_.leftCols(size_) = w_.leftCols(size_);
  for (int j = 0; j < k_; ++j) {
    const ContactData& c = contacts[static_cast<std::size_t>(index[static_cast<std::size_t>(j)])];
    if (slip_coupling[j] != 0.0) b_.col(j) += slip_coupling[j] * c.w_tangent;
  }
}

void ContactKinematics::delassus(const Matrix& a_inv, Eigen::Ref<Matrix> g) {
  const auto w = w_.leftCols(size_);
  auto a_inv_b = a_inv_b_.leftCols(size_);
  if (coupled_) {
    a_inv_b.noalias() = a_inv * b_.leftCols(size_);
  } else {
    a_inv_b.noalias() = a_inv * w;
  }
  g.noalias() = w.transpose() * a_inv_b;
}

void ContactKinematics::velocities(const std::vector<ContactData>& contacts,
                                   const std::vector<int>& index, const Vector& v,
                                   ContactLevel level, Eigen::Ref<Vector> out) const {
  const bool velocity = level == ContactLevel::kVelocity;
  for (int j = 0; j < k_; ++j) {
    const ContactData& c = contacts[static_cast<std::size_t>(index[static_cast<std::size_t>(j)])];
    out[j] = c.w_normal.dot(v) + (velocity ? c.what_normal : c.wbar_normal);
    if (size_ > k_) out[k_ + j] = c.w_tangent.dot(v) + (velocity ? c.what_tangent : c.wbar_tangent);
  }
}

void ContactKinematics::apply(const Eigen::Ref<const Vector>& lambda, Vector& v) const {
  v.noalias() += a_inv_b_.leftCols(size_) * lambda;
}

}  // namespace nsb::integrators
