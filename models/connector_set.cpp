#include "models/connector_set.hpp"
#include "models/field_checks.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace nsb::models {

namespace {

// A point fixed in a frame at pose (x, y, theta): the frame origin and the rotated offset.
Eigen::Vector2d rotated(double theta, const Eigen::Vector2d& r) {
  const double c = std::cos(theta), s = std::sin(theta);
  return {c * r.x() - s * r.y(), s * r.x() + c * r.y()};
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

ConnectorSet::ConnectorSet(const std::vector<parts::RigidBody>& bodies,
                           const std::vector<parts::PrescribedBody>& prescribed,
                           const std::vector<parts::Restrainer>& restrainers,
                           const std::vector<parts::GroundLink>& links,
                           parts::MotionTable& motions) {
  const auto nb = static_cast<int>(bodies.size());
  const auto np = static_cast<int>(prescribed.size());
  for (std::size_t i = 0; i < restrainers.size(); ++i) {
    const auto& r = restrainers[i];
    const std::string prefix = indexed("restrainers", i);
    require(r.body >= 0 && r.body < nb, prefix + "body", "must name one of the bodies");
    const bool on_body = r.other == parts::Obstacle::kBody;
    require(r.other_index >= 0 && r.other_index < (on_body ? nb : np), prefix + "other_index",
            on_body ? "must name one of the bodies" : "must name one of the prescribed bodies");
    require(!on_body || r.other_index != r.body, prefix + "other_index",
            "must be another body than anchor a's");
    require(r.anchor.allFinite() && r.other_anchor.allFinite(), prefix + "anchor",
            "must be finite [m]");
    r.cable.validate(prefix + "cable.");
    CableState c{.offset_a = 3 * r.body, .anchor_a = r.anchor, .anchor_b = r.other_anchor,
                 .cable = connectors::Cable(r.cable)};
    c.rest_a = bodies[static_cast<std::size_t>(r.body)].rest;
    Eigen::Vector2d pb;
    if (on_body) {
      c.offset_b = 3 * r.other_index;
      c.rest_b = bodies[static_cast<std::size_t>(r.other_index)].rest;
      pb = c.rest_b.head<2>() + rotated(c.rest_b.z(), r.other_anchor);
    } else {
      c.seat = r.other_index;
      pb = prescribed[static_cast<std::size_t>(r.other_index)].reference + r.other_anchor;
    }
    const Eigen::Vector2d pa = c.rest_a.head<2>() + rotated(c.rest_a.z(), r.anchor);
    c.rest_length = (pa - pb).norm();
    require(c.rest_length > 0, prefix + "anchor", "the two anchors must differ at rest");
    cables_.push_back(c);
  }
  for (std::size_t i = 0; i < links.size(); ++i) {
    const auto& l = links[i];
    const std::string prefix = indexed("links", i);
    require(l.body >= 0 && l.body < nb, prefix + "body", "must name one of the bodies");
    require(std::isfinite(l.position) &&
                std::abs(l.position) <= 0.5 * bodies[static_cast<std::size_t>(l.body)].length,
            prefix + "position", "must lie on the body, |s| <= L/2 [m]");
    l.longitudinal.validate(prefix + "longitudinal.");
    l.transverse.validate(prefix + "transverse.");
    links_.push_back({.body = l.body, .offset = 3 * l.body, .position = l.position,
                      .x = connectors::Law(l.longitudinal), .y = connectors::Law(l.transverse),
                      .ground_x = motions.add(l.ground_longitudinal, false),
                      .ground_y = motions.add(l.ground_transverse, false)});
  }
}

void ConnectorSet::add_initial_stiffness(int body, Eigen::Matrix3d& k0) const {
  for (const auto& l : links_) {
    if (l.body != body) continue;
    const Eigen::Vector3d by(0.0, 1.0, l.position);
    k0(0, 0) += l.x.initial_stiffness();
    k0 += l.y.initial_stiffness() * by * by.transpose();
  }
}

void ConnectorSet::set_quasi_static(int body, const Eigen::LDLT<Eigen::Matrix3d>& k0_bb) {
  for (auto& l : links_) {
    if (l.body != body) continue;
    l.qs_x = k0_bb.solve(Eigen::Vector3d(l.x.initial_stiffness(), 0.0, 0.0));
    l.qs_y = k0_bb.solve(l.y.initial_stiffness() * Eigen::Vector3d(0.0, 1.0, l.position));
  }
}

void ConnectorSet::add_support_velocity(int body, const parts::MotionTable& motions,
                                        Eigen::Vector3d& us) const {
  for (const auto& l : links_) {
    if (l.body != body) continue;
    us += l.qs_x * motions.value(l.ground_x).v + l.qs_y * motions.value(l.ground_y).v;
  }
}

template <bool kCommittedBranch>
void ConnectorSet::cable_force(CableState& c, const integrators::Vector& q,
                               const std::vector<PlanarMotion>& seats,
                               integrators::Vector& f) const {
  const Eigen::Vector3d pose_a = q.segment<3>(c.offset_a) + c.rest_a;
  const Eigen::Vector2d r_a = rotated(pose_a.z(), c.anchor_a);
  Eigen::Vector2d r_b, p_b;
  if (c.offset_b >= 0) {
    const Eigen::Vector3d pose_b = q.segment<3>(c.offset_b) + c.rest_b;
    r_b = rotated(pose_b.z(), c.anchor_b);
    p_b = pose_b.head<2>() + r_b;
  } else {
    const PlanarMotion& s = seats[static_cast<std::size_t>(c.seat)];
    r_b = rotated(s.position.z(), c.anchor_b);
    p_b = s.position.head<2>() + r_b;
  }
  const Eigen::Vector2d d = pose_a.head<2>() + r_a - p_b;
  const double length = d.norm();
  const Eigen::Vector2d e = length > 0 ? Eigen::Vector2d(d / length) : Eigen::Vector2d::Zero();
  c.j_a << e.x(), e.y(), cross(r_a, e);
  c.j_b << e.x(), e.y(), cross(r_b, e);
  c.r_b = r_b;
  const double elongation = length - c.rest_length;
  const double tension = kCommittedBranch ? c.cable.force_on_committed_branch(elongation)
                                          : c.cable.set_trial(elongation);
  f.segment<3>(c.offset_a) -= tension * c.j_a;
  if (c.offset_b >= 0) f.segment<3>(c.offset_b) += tension * c.j_b;
}

void ConnectorSet::forces(const integrators::Vector& q, const parts::MotionTable& motions,
                          const std::vector<PlanarMotion>& seats, integrators::Vector& f) {
  forces_of<false>(q, motions, seats, f);
}

void ConnectorSet::forces_on_committed_branches(const integrators::Vector& q,
                                                const parts::MotionTable& motions,
                                                const std::vector<PlanarMotion>& seats,
                                                integrators::Vector& f) {
  forces_of<true>(q, motions, seats, f);
}

template <bool kCommittedBranch>
void ConnectorSet::forces_of(const integrators::Vector& q, const parts::MotionTable& motions,
                             const std::vector<PlanarMotion>& seats, integrators::Vector& f) {
  for (auto& c : cables_) cable_force<kCommittedBranch>(c, q, seats, f);
  for (auto& l : links_) {
    const double s = l.position;
    const int o = l.offset;
    const double dx = q(o) - motions.value(l.ground_x).d;
    const double dy = q(o + 1) + s * q(o + 2) - motions.value(l.ground_y).d;
    const double fx = kCommittedBranch ? l.x.force_on_committed_branch(dx) : l.x.set_trial(dx);
    const double fy = kCommittedBranch ? l.y.force_on_committed_branch(dy) : l.y.set_trial(dy);
    f(o) -= fx;
    f(o + 1) -= fy;
    f(o + 2) -= s * fy;
  }
}

void ConnectorSet::tangent(integrators::Matrix& K) const {
  for (const auto& c : cables_) {
    const double k = c.cable.tangent();
    if (k == 0.0) continue;
    K.block<3, 3>(c.offset_a, c.offset_a) += k * c.j_a * c.j_a.transpose();
    if (c.offset_b < 0) continue;
    K.block<3, 3>(c.offset_b, c.offset_b) += k * c.j_b * c.j_b.transpose();
    K.block<3, 3>(c.offset_a, c.offset_b) -= k * c.j_a * c.j_b.transpose();
    K.block<3, 3>(c.offset_b, c.offset_a) -= k * c.j_b * c.j_a.transpose();
  }
  for (const auto& l : links_) {
    const double s = l.position;
    const int o = l.offset;
    const double kx = l.x.tangent(), ky = l.y.tangent();
    K(o, o) += kx;
    K(o + 1, o + 1) += ky;
    K(o + 1, o + 2) += ky * s;
    K(o + 2, o + 1) += ky * s;
    K(o + 2, o + 2) += ky * s * s;
  }
}

bool ConnectorSet::tangent_changed() const {
  for (const auto& c : cables_) {
    if (c.cable.tangent_changed()) return true;
  }
  for (const auto& l : links_) {
    if (l.x.tangent_changed() || l.y.tangent_changed()) return true;
  }
  return false;
}

void ConnectorSet::commit() {
  for (auto& c : cables_) c.cable.commit();
  for (auto& l : links_) {
    l.x.commit();
    l.y.commit();
  }
}

void ConnectorSet::revert() {
  for (auto& c : cables_) c.cable.revert();
  for (auto& l : links_) {
    l.x.revert();
    l.y.revert();
  }
}

double ConnectorSet::ground_power(const parts::MotionTable& motions,
                                  const std::vector<PlanarMotion>& seats) const {
  double p = 0.0;
  for (const auto& c : cables_) {
    if (c.offset_b >= 0) continue;
    const PlanarMotion& s = seats[static_cast<std::size_t>(c.seat)];
    const Eigen::Vector2d v_b =
        s.velocity.head<2>() + s.velocity.z() * Eigen::Vector2d(-c.r_b.y(), c.r_b.x());
    p -= c.cable.force() * c.j_b.head<2>().dot(v_b);
  }
  for (const auto& l : links_) {
    p -= l.x.force() * motions.value(l.ground_x).v + l.y.force() * motions.value(l.ground_y).v;
  }
  return p;
}

void ConnectorSet::energy(integrators::EnergyState& e) const {
  for (const auto& c : cables_) {
    e.stored += c.cable.stored_energy();
    e.hysteretic += c.cable.dissipated_energy();
  }
  for (const auto& l : links_) {
    e.stored += l.x.stored_energy() + l.y.stored_energy();
    e.hysteretic += l.x.dissipated_energy() + l.y.dissipated_energy();
  }
}

}  // namespace nsb::models
