// The claim runs at a point: the assumptions and their ranges, the runs of Fig. 6, the
// overrides of a point, and the sweep design of a set of points.
#include "paper-figures/claim_runs.hpp"

#include <toml++/toml.h>

#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "io/csv.hpp"
#include "io/files.hpp"
#include "paper-figures/figure.hpp"
#include "paper-figures/figures.hpp"
#include "scene/cosmos.hpp"
#include "scene/records.hpp"
#include "scene/scene.hpp"

namespace nsb::paper_figures {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// The assumptions and their plausible ranges (docs/bridge.md, "Assumed"; the reasons are
// repeated in docs/paper-figures.md, "Uncertainty of the verdicts"). None is tuned to a result.

const std::vector<Assumption>& assumptions() {
  static const std::vector<Assumption> a{
      {"deck_width", "deck width W", "m", 2.44, 2.13, 2.74, false,
       "8 ft at 1/4 scale is an estimate; +-1 ft (7-9 ft, prototype decks of 28-36 ft)"},
      {"height_bent1", "clear height of bent 1", "m", 1.83, 1.52, 2.13, false,
       "6 ft recalled to the foot; +-1 ft (stiffness ~ H^-3: -35 % ... +60 %)"},
      {"height_bent2", "clear height of bent 2", "m", 2.44, 2.13, 2.74, false,
       "8 ft recalled to the foot; +-1 ft"},
      {"height_bent3", "clear height of bent 3", "m", 1.52, 1.22, 1.83, false,
       "5 ft recalled to the foot; +-1 ft"},
      {"gap", "expansion gap at each end", "m", 0.0127, 0.00635, 0.01905, false,
       "a 2 in joint at 1/4 scale; prototype joints of 1-3 in"},
      {"friction", "friction coefficient mu", "-", 0.5, 0.3, 0.7, false,
       "the paper's 0.5 is not measured; +-0.2, as in scenes/sweeps/fig6.toml"},
      {"damping", "Rayleigh damping ratio, modes 1 and 3", "-", 0.08, 0.05, 0.11, false,
       "the paper's 8 % is its modelling choice, not measured; +-3 points"},
      {"time_scale", "time scale of the record", "-", 1.0, 0.5, 1.0, true,
       "either the record's own axis (1.0, the paper's event times) or the 1/4-scale "
       "similitude (0.5)"},
      {"seat_delay", "lag of the seat motion behind the ground", "s", 0.0, 0.0, 0.05, false,
       "the actuators followed a pre-test abutment model: a lag of up to a quarter of an "
       "abutment-backfill period of about 0.2 s"},
      {"seat_rotation", "seat rotation per seat displacement, c in phi = c u_x / W", "-", 0.0,
       -0.05, 0.05, false,
       "seat rotation unknown; an end-to-end mismatch of the seat's displacement of up to "
       "5 %"},
      {"longitudinal_ratio", "longitudinal-to-transverse PGA ratio", "-", 1.2, 1.0, 1.4, false,
       "\"about 1.2 g\" against \"about 1.0 g\" in runs 6-7; +-0.2"},
  };
  return a;
}

std::vector<double> nominal_point() {
  std::vector<double> v;
  for (const auto& a : assumptions()) v.push_back(a.nominal);
  return v;
}

std::vector<ClaimRun> fig6_runs(const std::vector<int>& pga_runs,
                                const std::vector<int>& mu0_runs) {
  std::vector<ClaimRun> r;
  for (int n : pga_runs) {
    r.push_back({"exc" + std::to_string(n), n, true, false});
    r.push_back({"exc" + std::to_string(n) + "-no-pounding", n, false, false});
  }
  for (int n : mu0_runs) r.push_back({"exc" + std::to_string(n) + "-mu0", n, true, true});
  return r;
}

namespace {

// Gaps that never close (the runs without pounding, as in the nominal figures).
constexpr double kNoPoundingGap = 1.0;  // [m]

}  // namespace

std::size_t assumption_index(const std::string& key) {
  const auto& a = assumptions();
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].key == key) return i;
  }
  throw std::logic_error("claim runs: no assumption " + key);
}

std::string override_text(const std::string& key, double v) {
  return key + "=" + io::csv_number(v);
}

std::vector<std::string> point_overrides(const std::vector<double>& v, const ClaimRun& run,
                                         const SceneTargets& targets) {
  if (v.size() != assumptions().size()) {
    throw std::invalid_argument("point_overrides: " + std::to_string(v.size()) + " values for " +
                                std::to_string(assumptions().size()) + " assumptions");
  }
  const auto ty = targets.transverse_pga.find(run.excitation);
  const auto tx = targets.longitudinal_pga.find(run.excitation);
  if (ty == targets.transverse_pga.end() || tx == targets.longitudinal_pga.end()) {
    throw std::invalid_argument("point_overrides: no targets for excitation " +
                                std::to_string(run.excitation));
  }
  auto at = [&](const char* key) { return v[assumption_index(key)]; };
  const double width = at("deck_width"),
               gap = run.pounding ? at("gap") : kNoPoundingGap;
  // The scenes' longitudinal targets are 1.2 times the transverse ones (docs/bridge.md); the
  // ratio scales them, so that the nominal ratio gives the scenes' values exactly.
  const double nominal_ratio = assumptions()[assumption_index("longitudinal_ratio")].nominal;
  const double pga_x = tx->second * (at("longitudinal_ratio") / nominal_ratio);
  std::vector<std::string> o{
      override_text("model.excitation.target_pga", ty->second),
      override_text("model.excitation.longitudinal_pga", pga_x),
      override_text("model.deck.width", width),
      override_text("model.bents.0.height", at("height_bent1")),
      override_text("model.bents.1.height", at("height_bent2")),
      override_text("model.bents.2.height", at("height_bent3")),
      override_text("model.gaps.left", gap),
      override_text("model.gaps.right", gap),
      override_text("model.seats.friction", run.mu0 ? 0.0 : at("friction")),
      override_text("model.damping.ratio_i", at("damping")),
      override_text("model.damping.ratio_j", at("damping")),
      override_text("model.excitation.time_scale", at("time_scale")),
      override_text("model.seats.delay_left", at("seat_delay")),
      override_text("model.seats.delay_right", at("seat_delay")),
  };
  // Seat rotation phi = c u_x / W: the longitudinal record, read as an angular acceleration
  // and processed as the seats' displacement is (same time scale, baseline correction and
  // delay), scaled by c / W times the longitudinal record's amplitude factor.
  if (const double c = at("seat_rotation"); c != 0.0) {
    if (targets.rotation_record.empty()) {
      throw std::invalid_argument("point_overrides: a seat rotation needs the rotation record "
                                  "(write_rotation_record)");
    }
    const double factor = pga_x / targets.longitudinal_record_pga;
    for (const char* side : {"left", "right"}) {
      o.push_back(std::string("model.seats.rotation_record_") + side + "=" +
                  targets.rotation_record.string());
    }
    o.push_back(override_text("model.seats.rotation_scale", c / width * factor));
  }
  if (run.factor > 0) {
    for (auto& s : compliance_overrides(run.factor, run.law)) o.push_back(std::move(s));
  }
  if (run.factor > 0 && run.tolerance > 0) {
    o.push_back(override_text("solver.tolerance", run.tolerance));
  }
  return o;
}

SceneTargets scene_targets(const fs::path& scenes, const std::vector<ClaimRun>& runs) {
  SceneTargets t;
  std::vector<ClaimRun> all = runs;
  all.push_back({"base", kBaseExcitation, true, false});
  for (const auto& r : all) {
    const fs::path file = scenes / ("bridge-exc" + std::to_string(r.excitation) + ".toml");
    toml::table root;
    try {
      root = toml::parse_file(file.string());
    } catch (const toml::parse_error& e) {
      throw std::invalid_argument(file.string() + ": " + std::string(e.description()));
    }
    const auto y = root["model"]["excitation"]["target_pga"].value<double>();
    const auto x = root["model"]["excitation"]["longitudinal_pga"].value<double>();
    if (!y || !x) {
      throw std::invalid_argument(file.string() +
                                  ": model.excitation.target_pga and longitudinal_pga required");
    }
    t.transverse_pga[r.excitation] = *y;
    t.longitudinal_pga[r.excitation] = *x;
    if (r.excitation == kBaseExcitation) {
      const auto rec = root["model"]["excitation"]["longitudinal_record"].value<std::string>();
      if (!rec) throw std::invalid_argument(file.string() + ": longitudinal_record required");
      t.longitudinal_record = *rec;
    }
  }
  // The longitudinal record's own PGA: the base scene with both targets off (factor 1).
  const scene::Scene raw =
      scene::load_scene(scenes / ("bridge-exc" + std::to_string(kBaseExcitation) + ".toml"),
                         {"model.excitation.target_pga=0", "model.excitation.longitudinal_pga=0"});
  t.longitudinal_record_pga = input_pga(raw, false);
  if (!(t.longitudinal_record_pga > 0)) {
    throw std::invalid_argument("scene_targets: the longitudinal record has no acceleration");
  }
  // input_pga found the record, so the base scene has a design, a bent and its motion.
  t.longitudinal_record_file = raw.design->excitation.bents[0].longitudinal->source();
  return t;
}

fs::path write_rotation_record(const SceneTargets& targets, const fs::path& dir) {
  const fs::path& source = targets.longitudinal_record_file;
  if (source.empty()) {
    throw std::invalid_argument("write_rotation_record: no longitudinal record file "
                                "(scene_targets)");
  }
  const models::Record r = scene::read_at2(source, scene::kStandardGravity);
  fs::create_directories(dir);
  const fs::path out = dir / ("seat-rotation-" + source.stem().string() + ".txt");
  std::ostringstream text;
  text << "# " << source.filename().string()
       << ": the ground acceleration [m/s^2] read as the seats' angular acceleration [rad/s^2]\n"
       << "# (the seat-rotation assumption, docs/paper-figures.md); t [s], a [rad/s^2]\n";
  text << std::setprecision(17);
  for (std::size_t i = 0; i < r.t.size(); ++i) text << r.t[i] << ' ' << r.a[i] << '\n';
  io::write_file_atomically(out, text.str());
  return fs::absolute(out);
}

sweep::Design make_design(const std::string& name, const fs::path& base_scene,
                          const std::vector<Point>& points, const SceneTargets& targets,
                          double end_time, const std::vector<ClaimRun>& claim_set,
                          const std::function<bool(const Point&, const ClaimRun&)>& wanted) {
  sweep::Design d;
  d.file = base_scene;
  d.scene = base_scene;
  d.mode = sweep::Mode::kList;
  d.factors.push_back({"point", {}, std::nullopt, 0});
  d.factors.push_back({"claim_run", {}, std::nullopt, 0});
  for (const auto& a : assumptions()) d.factors.push_back({a.key, {}, std::nullopt, 0});
  std::size_t id = 0;
  for (const auto& p : points) {
    for (const auto& r : claim_set) {
      if (!wanted(p, r)) continue;
      sweep::Run run;
      std::ostringstream s;
      s << std::setw(5) << std::setfill('0') << id++;
      run.id = s.str();
      run.labels = {p.name, r.name};
      run.labels.insert(run.labels.end(), p.labels.begin(), p.labels.end());
      run.overrides = sweep::parse_overrides(point_overrides(p.values, r, targets));
      if (end_time > 0)
        run.overrides.push_back(
            scene::parse_override(override_text("solver.end_time", end_time)));
      d.runs.push_back(std::move(run));
    }
  }
  sweep::load_base_scene(d);
  d.hash = name + "-" + std::to_string(d.runs.size());
  return d;
}

}  // namespace nsb::paper_figures
