// A broken shear key (docs/bridge.md, "Shear keys"), under Moreau–Jean on
// scenes/bridge-shear-keys-capacity.toml:
//  - before its first break at t_b the run equals the run with unbreakable keys
//    (scenes/bridge-shear-keys.toml);
//  - the whole run equals a run with unbreakable keys whose key contacts are simply deleted
//    (far for good) from the end of the step of each break on: a break changes nothing but the
//    contact's presence, and carries the state (q, u, the bents' committed Takeda states) on
//    as the run without the key would;
//  - the comparison catches a deliberate break one step early (the key gone before the impact
//    that broke it): it then differs. (One step late it does not: the key's impact ends in
//    its step, ε = 0, and the deck leaves the key.)
// All to 1e-9 of each column's peak.
#include "integrators/moreau_jean.hpp"
#include "models/scene.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace ni = nsb::integrators;
namespace nm = nsb::models;

constexpr double kWindow = 4.5;  // [s], past the first break (3.74 s)
constexpr double kRelative = 1e-9;

// When a contact goes: its 0-based slot and the time [s].
struct Deletion {
  int slot = 0;
  double at = 0.0;
};

// Delegates to `inner` and deletes each contact of `deletions` (far for good) from the end of
// the first accepted step at or after its time on.
class DeletedContacts final : public ni::System {
 public:
  DeletedContacts(ni::System& inner, std::vector<Deletion> deletions)
      : s_(inner), deletions_(std::move(deletions)), deleted_(deletions_.size(), 0) {}
  int dofs() const override { return s_.dofs(); }
  std::vector<std::string> coordinate_names() const override { return s_.coordinate_names(); }
  std::vector<std::string> velocity_names() const override { return s_.velocity_names(); }
  const ni::Matrix& mass() const override { return s_.mass(); }
  double initial_time() const override { return s_.initial_time(); }
  ni::Vector initial_position() const override { return s_.initial_position(); }
  ni::Vector initial_velocity() const override { return s_.initial_velocity(); }
  void forces(double t, const ni::Vector& q, const ni::Vector& u, ni::Vector& f) override {
    s_.forces(t, q, u, f);
  }
  void tangent(double t, const ni::Vector& q, const ni::Vector& u, ni::Matrix& K,
               ni::Matrix& C) override {
    s_.tangent(t, q, u, K, C);
  }
  bool tangent_changed() const override { return s_.tangent_changed(); }
  void commit() override { s_.commit(); }
  void revert() override { s_.revert(); }
  int contacts() const override { return s_.contacts(); }
  void contact_data(double t, const ni::Vector& q, const ni::Vector& u,
                    std::vector<ni::ContactData>& out) const override {
    s_.contact_data(t, q, u, out);
    mark(out);
  }
  void contact_normals(double t, const ni::Vector& q, const ni::Vector& u,
                       std::vector<ni::ContactData>& out) const override {
    s_.contact_normals(t, q, u, out);
    mark(out);
  }
  ni::StepVerdict accept_step(const ni::AcceptedStep& step) override {
    for (std::size_t k = 0; k < deletions_.size(); ++k) {
      if (step.t >= deletions_[k].at) deleted_[k] = 1;
    }
    return ni::StepVerdict::kContinue;
  }
  ni::PowerTerms power(double t, const ni::Vector& q, const ni::Vector& u) const override {
    return s_.power(t, q, u);
  }
  ni::EnergyState energy(double t, const ni::Vector& q) const override {
    return s_.energy(t, q);
  }

 private:
  void mark(std::vector<ni::ContactData>& out) const {
    for (std::size_t k = 0; k < deletions_.size(); ++k) {
      if (deleted_[k]) out[static_cast<std::size_t>(deletions_[k].slot)].far = true;
    }
  }

  ni::System& s_;
  std::vector<Deletion> deletions_;
  std::vector<char> deleted_;
};

nm::Scene load(const std::string& name) {
  return nm::load_scene(std::string(NSB_SCENES_DIR) + "/" + name,
                        {"solver.end_time=" + std::to_string(kWindow), "solver.method=moreau"});
}

ni::Recorder run(ni::System& s, const ni::RunConfig& config) {
  ni::Recorder rec(s, 0.0);
  const ni::RunResult r = ni::moreau_jean(s, std::get<ni::MoreauJeanOptions>(config), rec);
  REQUIRE(ni::succeeded(r.status));
  return rec;
}

// Largest difference of a and b over rows with t < until, relative to each column's peak.
double difference(const ni::Recorder& a, const ni::Recorder& b, double until) {
  REQUIRE(a.rows() == b.rows());
  double worst = 0.0;
  for (std::size_t c = 1; c < a.columns().size(); ++c) {
    double peak = 1e-300;
    for (std::size_t r = 0; r < a.rows(); ++r) peak = std::max(peak, std::abs(a.at(r, c)));
    for (std::size_t r = 0; r < a.rows() && a.at(r, 0) < until; ++r) {
      worst = std::max(worst, std::abs(a.at(r, c) - b.at(r, c)) / peak);
    }
  }
  return worst;
}

TEST_CASE("a broken shear key: the run without the key from the break on") {
  nm::Scene breaking = load("bridge-shear-keys-capacity.toml");
  const ni::Recorder broken = run(*breaking.system, breaking.run);
  // The first break, from the limit states.
  double t_b = std::numeric_limits<double>::infinity();
  int slot = -1;
  for (const auto& v : breaking.system->limit_states()) {
    if (v.exceeded && v.time < t_b) {
      t_b = v.time;
      slot = v.removes_contact - 1;
    }
  }
  REQUIRE(slot >= 4);
  CHECK(t_b < kWindow);
  INFO("first break at t = ", t_b, " s, contact ", slot + 1);

  nm::Scene whole = load("bridge-shear-keys.toml");
  const ni::Recorder unbreakable = run(*whole.system, whole.run);
  MESSAGE("before the break, against unbreakable keys: ", difference(broken, unbreakable, t_b));
  CHECK(difference(broken, unbreakable, t_b) <= kRelative);
  CHECK(difference(broken, unbreakable, kWindow + 1.0) > 1e-6);  // the break matters

  // Every break of the window, as a deletion of its contact.
  std::vector<Deletion> breaks;
  for (const auto& v : breaking.system->limit_states()) {
    if (v.exceeded) breaks.push_back({v.removes_contact - 1, v.time});
  }
  MESSAGE(breaks.size(), " keys break in the window");
  const double t_all = kWindow + 1.0;
  nm::Scene base = load("bridge-shear-keys.toml");
  DeletedContacts deleted(*base.system, breaks);
  const ni::Recorder without = run(deleted, base.run);
  MESSAGE("the whole window, against the keys deleted at their breaks: ",
          difference(broken, without, t_all));
  CHECK(difference(broken, without, t_all) <= kRelative);

  // A deliberate break one step early is caught.
  const double h = std::get<ni::MoreauJeanOptions>(base.run).step;
  nm::Scene early_scene = load("bridge-shear-keys.toml");
  std::vector<Deletion> wrong = breaks;
  for (Deletion& b : wrong) {
    if (b.slot == slot) b.at = t_b - 1.5 * h;
  }
  DeletedContacts early(*early_scene.system, wrong);
  const ni::Recorder early_run = run(early, early_scene.run);
  MESSAGE("the first key deleted one step early: ", difference(broken, early_run, t_all));
  CHECK(difference(broken, early_run, t_all) > 1e-6);
}

}  // namespace
