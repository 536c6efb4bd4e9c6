// The assembly's optional history columns (integrators::OutputGroup; docs/outputs.md): the
// bents' deformations and forces, the bodies relative to the ground, and the ground motion of
// the reference support. Evaluated only when a run asks for a group, after the step's commit;
// nothing here changes the state the integration reads (the motion cache holds pure functions
// of t, the springs are read, not set).
#include "models/assembly.hpp"

#include <cmath>

namespace nsb::models {

using integrators::OutputGroup;

std::pair<parts::Motion, parts::Motion> Assembly::reference_ground() const {
  for (const auto& b : parts_.bents) {
    if (b.ground_longitudinal || b.ground_transverse) {
      return {b.ground_longitudinal, b.ground_transverse};
    }
  }
  if (!parts_.prescribed.empty()) {
    return {parts_.prescribed.front().longitudinal, parts_.prescribed.front().transverse};
  }
  return {};
}

namespace {

// prefix + number + suffix, appended piece by piece (GCC 12's -Wrestrict misreads
// "literal" + std::string&& as an overlapping copy).
std::string numbered(const char* prefix, std::size_t number, const char* suffix) {
  std::string name = prefix;
  name += std::to_string(number);
  name += suffix;
  return name;
}

}  // namespace

std::vector<std::string> Assembly::output_columns(OutputGroup g) const {
  std::vector<std::string> names;
  switch (g) {
    case OutputGroup::kBents:
      for (std::size_t i = 1; i <= parts_.bents.size(); ++i) {
        for (const char* s : {"_ux", "_uy", "_fx", "_fy"}) names.push_back(numbered("bent", i, s));
      }
      break;
    case OutputGroup::kRelative:
      for (std::size_t b = 1; b <= parts_.bodies.size(); ++b) {
        names.push_back(numbered("x", b, "_rel"));
        names.push_back(numbered("y", b, "_rel"));
      }
      for (std::size_t b = 1; b <= parts_.bodies.size(); ++b) {
        for (std::size_t k = 1; k <= 4; ++k) {
          const std::string c = numbered("corner", b, "_") + std::to_string(k);
          names.push_back(c + "_x_rel");
          names.push_back(c + "_y_rel");
        }
      }
      break;
    case OutputGroup::kGround:
      names = {"ground_ux", "ground_uy", "ground_vx", "ground_vy", "ground_ax", "ground_ay"};
      break;
    default:
      break;
  }
  return names;
}

namespace {

// The force a Takeda spring gives at deformation d, moved there from its committed state by
// the general rules (the committed force itself when d is the committed deformation: a row
// at the end of an accepted step).
double spring_force(const takeda::Spring& s, double d) {
  const takeda::State& c = s.committed_state();
  return d == c.d ? c.f : s.moved(c, d).f;
}

GroundMotion::Values motion_values(const parts::Motion& m, double t) {
  return m ? m->values(t) : GroundMotion::Values{};
}

}  // namespace

void Assembly::output_values(OutputGroup g, double t, const integrators::Vector& q,
                             const integrators::Vector& /*u*/, double* out) const {
  switch (g) {
    case OutputGroup::kBents: {
      update_motions(t);
      for (std::size_t j = 0; j < parts_.bents.size(); ++j) {
        const BentState& b = bents_[bent_slot_[j]];
        const int o = b.offset;
        const double gx = motions_.value(b.ground_x).d, gy = motions_.value(b.ground_y).d;
        if (!b.general) {
          // The deformation its springs see (forces_of), and the force they exert on the body.
          const double dx = q(o) - gx;
          const double dy = q(o + 1) + b.position * q(o + 2) - gy;
          *out++ = dx;
          *out++ = dy;
          *out++ = -spring_force(b.x, dx);
          *out++ = -spring_force(b.y, dy);
          continue;
        }
        // A bent with columns, in its own axes (normal to its line and along it): the mean of
        // its columns' deformations and the sum of their forces, so that force against
        // deformation is the bent's loop (equal columns deform alike without twist).
        const std::size_t n = bent_columns_[j];
        double dx = 0.0, dy = 0.0, fx = 0.0, fy = 0.0;
        for (std::size_t c = 0; c < n; ++c) {
          const BentState& column = bents_[bent_slot_[j] + c];
          const double cx = column.deformation_x(q, o, gx, gy);
          const double cy = column.deformation_y(q, o, gx, gy);
          dx += cx;
          dy += cy;
          fx += spring_force(column.x, cx);
          fy += spring_force(column.y, cy);
        }
        *out++ = dx / static_cast<double>(n);
        *out++ = dy / static_cast<double>(n);
        *out++ = -fx;
        *out++ = -fy;
      }
      break;
    }
    case OutputGroup::kRelative: {
      const auto [mx, my] = reference_ground();
      const double gx = mx ? mx->displacement(t) : 0.0;
      const double gy = my ? my->displacement(t) : 0.0;
      const std::size_t n = parts_.bodies.size();
      for (std::size_t b = 0; b < n; ++b) {
        *out++ = q(static_cast<Eigen::Index>(3 * b)) - gx;
        *out++ = q(static_cast<Eigen::Index>(3 * b + 1)) - gy;
      }
      for (std::size_t b = 0; b < n; ++b) {
        const parts::RigidBody& body = parts_.bodies[b];
        const Eigen::Vector3d d = q.segment<3>(static_cast<Eigen::Index>(3 * b));
        const Eigen::Rotation2Dd rest(body.rest(2)), now(body.rest(2) + d(2));
        for (int k = 0; k < 4; ++k) {
          // The corner's displacement from its rest position, exact in the rotation.
          const Eigen::Vector2d r = body.corner(k);
          const Eigen::Vector2d disp = d.head<2>() + now * r - rest * r;
          *out++ = disp(0) - gx;
          *out++ = disp(1) - gy;
        }
      }
      break;
    }
    case OutputGroup::kGround: {
      const auto [mx, my] = reference_ground();
      const GroundMotion::Values x = motion_values(mx, t), y = motion_values(my, t);
      for (double v : {x.displacement, y.displacement, x.velocity, y.velocity, x.acceleration,
                       y.acceleration}) {
        *out++ = v;
      }
      break;
    }
    default:
      break;
  }
}

}  // namespace nsb::models
