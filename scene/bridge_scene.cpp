// The bridge of a scene file (docs/bridge.md): its tables read by field
// (scene/scene_schema.hpp), in the order of the model: the deck, its gaps, the damping, the
// bents, the seats, the excitation, and the support motions made from the records.
#include "scene/scene_builders.hpp"

#include "io/csv.hpp"
#include "models/bridge_fields.hpp"
#include "models/bridge_parts.hpp"
#include "models/excitation_scaling.hpp"
#include "models/ground_motion.hpp"
#include "scene/bridge_part_kinds.hpp"
#include "scene/records.hpp"
#include "scene/scene_schema.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <numbers>
#include <optional>

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

namespace {

namespace fs = std::filesystem;

constexpr double kStandardGravity = 9.81;  // [m/s^2]: target PGA in scenes is in units of g

// Finds a record file: absolute, next to the scene, in ../data/ beside it, or in ./data/.
fs::path find_record(const Section& s, const std::string& key, const std::string& name) {
  const Source& c = s.context();
  const fs::path p(name);
  std::vector<fs::path> tried;
  if (p.is_absolute()) {
    tried.push_back(p);
  } else {
    tried.push_back(c.dir / p);
    tried.push_back(c.dir / ".." / "data" / p);
    tried.push_back(fs::current_path() / "data" / p);
  }
  for (const auto& t : tried) {
    std::error_code ec;
    if (fs::is_regular_file(t, ec)) return t;
  }
  std::string list;
  for (const auto& t : tried) list += (list.empty() ? "" : ", ") + t.lexically_normal().string();
  s.fail(key, "record file \"" + name + "\" not found (looked for " + list + ")");
}

// What table s says of its records: the unit of their values (unit_key, given or its
// default), the step of a file of values only (dt_key), and whether they are angular.
RecordKeys record_keys(const Section& s, const char* unit_key, double unit, const char* dt_key,
                       double dt, bool angular) {
  RecordKeys k;
  k.unit = unit;
  if (s.has(unit_key)) k.unit_key = s.key_path(unit_key);
  k.dt = dt;
  k.dt_key = s.key_path(dt_key);
  k.angular = angular;
  return k;
}

Record read_record(const Section& s, const std::string& key, const std::string& name,
                   const RecordKeys& keys) {
  const Source& c = s.context();
  const fs::path path = find_record(s, key, name);
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  if (ext == ".at2" && keys.angular) {
    s.fail(key, "record \"" + path.string() + "\" is an .AT2 file of ground accelerations in "
                "g; a rotation record is a text or CSV file in rad/s^2");
  }
  Record r;
  try {
    if (ext == ".at2") {
      r = read_at2(path, kStandardGravity, keys);
    } else if (ext == ".csv") {
      r = read_csv(path, keys);
    } else {
      r = read_two_column(path, keys);
    }
  } catch (const std::exception& e) {
    s.fail(key, "cannot read record \"" + path.string() + "\": " + e.what());
  }
  if (r.t.size() < 2 || r.t.size() != r.a.size()) {
    s.fail(key, "record \"" + path.string() + "\" needs at least 2 samples of (t, a)");
  }
  for (std::size_t i = 1; i < r.t.size(); ++i) {
    if (!(r.t[i] > r.t[i - 1])) {
      s.fail(key, "record \"" + path.string() + "\": time is not strictly increasing at sample " +
                      std::to_string(i + 1) + " (t = " + config::format_value(r.t[i]) + " s after " +
                      config::format_value(r.t[i - 1]) + " s)");
    }
  }
  for (std::size_t i = 0; i < r.a.size(); ++i) {
    if (!std::isfinite(r.a[i]) || !std::isfinite(r.t[i])) {
      s.fail(key, "record \"" + path.string() + "\": non-finite value at sample " +
                      std::to_string(i + 1));
    }
  }
  for (std::size_t i = 1; i < r.t.size(); ++i) {
    const double dt = r.t[i] - r.t[i - 1];
    if (c.record_step == 0.0 || dt < c.record_step) c.record_step = dt;
  }
  return r;
}

double peak(const Record& r) {
  double p = 0.0;
  for (double a : r.a) p = std::max(p, std::abs(a));
  return p;
}

// Ground motions of one direction, one per distinct delay (shared by the supports).
class MotionSet {
 public:
  MotionSet() = default;
  // offset: the record's place in a sequence [s], added to every delay (0: the record alone).
  MotionSet(std::optional<Record> r, GroundMotionOptions o, double offset = 0.0)
      : record_(std::move(r)), options_(o), offset_(offset) {}
  parts::Motion at_delay(double delay) {
    if (!record_) return nullptr;
    auto& m = cache_[delay];
    if (!m) {
      GroundMotionOptions o = options_;
      o.delay = offset_ == 0.0 ? delay : delay + offset_;
      m = std::make_shared<const GroundMotion>(*record_, o);
    }
    return m;
  }

 private:
  std::optional<Record> record_;
  GroundMotionOptions options_;
  double offset_ = 0.0;
  std::map<double, parts::Motion> cache_;
};

// Reads the sub-table `key` of [model] with fields into p; p keeps its values when the
// table is absent. Returns the table's section, or nullopt.
template <class S>
std::optional<Section> read_table(const Section& m, std::string_view key,
                                  std::span<const config::Field<S>> fields, S& p) {
  const auto* t = m.subtable(key);
  if (t == nullptr) return std::nullopt;
  Section s(m.context(), *t, m.key_path(key));
  s.only(keys_of(fields));
  s.read_all(fields, p);
  return s;
}

void read_damping(const Section& m, BridgeDesign& p) {
  const auto s = read_table(m, "damping", bridge_damping_fields(), p);
  if (s && p.damping_mode_i == p.damping_mode_j) s->fail("mode_j", "must differ from mode_i");
}

// The spring of one direction of a bent: explicit stiffness and yield force where given, the
// column design's values otherwise.
takeda::Parameters bent_spring(const Section& s, const BentSettings& b, const char* direction) {
  const std::string sk = std::string("stiffness_") + direction;
  const std::string fk = std::string("yield_force_") + direction;
  const bool stiff = s.has(sk), fy = s.has(fk);
  if ((!stiff || !fy) && !s.has("height")) {
    s.fail_table("missing key height (needed to derive " + (stiff ? fk : sk) +
                 "; give height, or both " + sk + " and " + fk + ")");
  }
  const bool longitudinal = std::string_view(direction) == "longitudinal";
  const double kk = stiff ? (longitudinal ? b.stiffness_longitudinal : b.stiffness_transverse)
                          : b.design.stiffness();
  const double ff = fy ? (longitudinal ? b.yield_force_longitudinal : b.yield_force_transverse)
                       : b.design.yield_force();
  const takeda::Parameters spring = takeda::Parameters::bilinear(
      ff, ff / kk, b.design.post_yield_ratio, b.design.unloading_exponent);
  // The spring's stiffness k, yield force f_y and yield displacement f_y / k, derived from
  // the column design or given, obey the bound of a scene number (kMaxMagnitude): positive,
  // within 1e-100 ... 1e100. A height of 1e-100 m gives k ~ 1e305 kN/m, whose natural
  // frequencies no eigenproblem resolves; a diameter of 1e99 m an infinite k.
  const double dy = ff / kk;
  const auto normal = [](double x) {
    return std::isfinite(x) && x >= 1.0 / kMaxMagnitude && x <= kMaxMagnitude;
  };
  bool takeda_ok = true;
  try {
    spring.validate();
  } catch (const std::invalid_argument&) {
    takeda_ok = false;
  }
  if (!(normal(kk) && normal(ff) && normal(dy) && takeda_ok)) {
    const auto value = [](double x, const char* unit) {
      return std::isfinite(x) ? six_digits(x) + " " + unit : derived(x);
    };
    const std::string what = std::string(direction) + " stiffness k = " + value(kk, "kN/m") +
                             ", yield force f_y = " + value(ff, "kN") +
                             " and yield displacement f_y / k = " + value(dy, "m");
    if (stiff && fy) {
      s.fail(sk, "with " + fk + ", gives a " + what +
                     "; expected positive numbers within 1e-100 ... 1e+100");
    }
    // The design key furthest from its default (in orders of magnitude) is the likely cause.
    const BentDesign defaults;
    const std::array<std::pair<const char*, std::pair<double, double>>, 5> design{{
        {"height", {b.design.height, 5.0}},
        {"column_diameter", {b.design.column_diameter, defaults.column_diameter}},
        {"elastic_modulus", {b.design.elastic_modulus, defaults.elastic_modulus}},
        {"cracked_ratio", {b.design.cracked_ratio, defaults.cracked_ratio}},
        {"yield_strain", {b.design.yield_strain, defaults.yield_strain}},
    }};
    const char* cause = "height";
    double furthest = -1.0;
    std::string inputs;
    for (const auto& [key, v] : design) {
      if (!s.has(key)) continue;
      inputs += (inputs.empty() ? "" : ", ") + std::string(key) + " = " + six_digits(v.first) +
                (std::string_view(key) == "elastic_modulus" ? " kPa"
                 : std::string_view(key) == "height" || std::string_view(key) == "column_diameter"
                     ? " m"
                     : "");
      const double distance = std::abs(std::log10(v.first / v.second));
      if (!(distance <= furthest)) {
        furthest = distance;
        cause = key;
      }
    }
    inputs += ", columns = " + std::to_string(b.design.columns);
    s.fail(cause, "the column design (" + inputs + ") gives a " + what +
                      " (k = 12 n E I_eff / H^3, f_y = k 2.25 eps_y H^2 / (6 d)); expected "
                      "positive numbers within 1e-100 ... 1e+100");
  }
  return spring;
}

// [[model.bents]]: the bents, the segment each carries and their wave-passage delays [s].
// lengths: the length of each segment ({deck length} with [model.deck]).
// heights: each bent's `height` [m], 0 where absent; need_height: [model.limit_states]
// drift_ratio is given, so every bent must give its height.
struct BentsRead {
  std::vector<double> delays;
  std::vector<int> segments;
  std::vector<double> heights;
};

// A curved deck of radius R subtending angle_deg = phi has the arc L = R phi: a bent
// beyond its ends at -+L/2 means that the radius cannot hold the deck. The error names the
// radius (the key that set the arc's length), the arc, the bent and the radius it needs.
[[noreturn]] void arc_error(const Section& deck, const DeckGeometry& plan, std::size_t bent,
                            double position) {
  const double phi = plan.subtended_angle();
  char text[400];
  std::snprintf(text, sizeof text,
                "R = %.6g m subtending angle_deg = %.6g gives an arc of %.6g m, its ends at "
                "-+%.6g m from its middle: it cannot hold [[model.bents]] %zu at position = "
                "%.6g m, which needs R >= 2 |position| / phi = %.6g m",
                plan.radius, phi * 180.0 / std::numbers::pi, plan.length, 0.5 * plan.length,
                bent, position, 2.0 * std::abs(position) / phi);
  deck.fail("radius", text);
}

// arc: the deck's table when it is curved and its arc is R phi (angle_deg given), else null.
BentsRead read_bents(const Section& m, const std::vector<double>& lengths, BridgeDesign& p,
                     bool need_height, const Section* arc) {
  BentsRead out;
  const bool one = !m.has("segments");
  const auto* bents = m.array_of_tables("bents");
  if (one && (bents == nullptr || bents->size() < 2)) {
    m.fail(bents == nullptr ? "kind" : "bents",
           "a bridge needs at least 2 [[model.bents]] (torsional stiffness)");
  }
  if (bents == nullptr) m.fail_table("missing [[model.bents]] (two per segment at least)");
  for (std::size_t j = 0; j < bents->size(); ++j) {
    Section s(m.context(), *(*bents)[j].as_table(),
              m.key_path("bents") + "[" + std::to_string(j) + "]");
    s.only(keys_of(BentSettings::fields()));
    BentSettings b;
    s.read_all(BentSettings::fields(), b);
    if (!s.has("position")) {
      s.fail_table("missing key position (bent position along the deck axis [m])");
    }
    if (static_cast<std::size_t>(b.segment) >= lengths.size()) {
      s.fail("segment", one ? "must be 0: [model.deck] is one segment"
                            : "must name one of the " + std::to_string(lengths.size()) +
                                  " [[model.segments]], 0 .. " +
                                  std::to_string(lengths.size() - 1) + " (0-based)");
    }
    const double half = 0.5 * lengths[static_cast<std::size_t>(b.segment)];
    if (std::abs(b.position) > half) {
      if (arc != nullptr) arc_error(*arc, p.deck, j, b.position);
      s.fail("position", (one ? std::string("must lie on the deck, |position| <= length / 2 = ")
                              : "must lie on segment " + std::to_string(b.segment) +
                                    ", |position| <= its length / 2 = ") +
                             config::format_value(half) + " m (got " +
                             config::format_value(b.position) + ")");
    }
    if (s.has("column_offsets") &&
        b.column_offsets.size() != static_cast<std::size_t>(b.design.columns)) {
      s.fail("column_offsets", "must give one offset per column: " +
                                   std::to_string(b.column_offsets.size()) + " offsets for "
                                   "columns = " + std::to_string(b.design.columns));
    }
    p.bents.push_back({b.position, bent_spring(s, b, "longitudinal"),
                       bent_spring(s, b, "transverse"), b.column_offsets, b.skew_deg});
    out.delays.push_back(b.delay);
    out.segments.push_back(b.segment);
    if (need_height && !s.has("height")) {
      s.fail_table("missing key height (bent height H [m], needed by [model.limit_states] "
                   "drift_ratio)");
    }
    out.heights.push_back(s.has("height") ? b.design.height : 0.0);
  }
  return out;
}

// [model.seats]: the seats' motion.
struct SeatMotions {
  std::array<double, 2> delays{0.0, 0.0};         // wave-passage delay of each seat [s]
  bool transverse = false;                        // seats follow the transverse record too
  std::array<std::optional<Record>, 2> rotation;  // angular acceleration records [rad/s^2]
  double rotation_scale = 1.0;                    // factor on the rotation records
};

SeatMotions read_seats(const Section& m, BridgeDesign& p) {
  SeatMotions out;
  const auto* t = m.subtable("seats");
  if (t == nullptr) return out;
  Section s(m.context(), *t, m.key_path("seats"));
  // The seat length belongs to the abutment's own table, beside its backfill and restrainer.
  if (s.has("seat_length")) {
    s.fail("seat_length", "the abutments' seat length is a key of [model.abutments] "
                          "(seat_length), a hinge's of its [[model.hinges]] element; "
                          "[model.seats] holds the seats' contact law and motion");
  }
  std::vector<std::string_view> keys = keys_of(bridge_seat_fields());
  for (const auto& k : keys_of(SeatMotionSettings::fields())) keys.push_back(k);
  s.only(keys);
  s.read_all(bridge_seat_fields(), p);
  SeatMotionSettings seats;
  s.read_all(SeatMotionSettings::fields(), seats);
  out.transverse = seats.transverse;
  out.delays = {seats.delay_left, seats.delay_right};
  out.rotation_scale = seats.rotation_scale;
  const std::array<std::pair<const char*, const std::string*>, 2> records{
      {{"rotation_record_left", &seats.rotation_record_left},
       {"rotation_record_right", &seats.rotation_record_right}}};
  for (std::size_t a = 0; a < 2; ++a) {
    if (records[a].second->empty()) continue;
    out.rotation[a] = read_record(s, records[a].first, *records[a].second,
                                  record_keys(s, "rotation_unit", seats.rotation_unit,
                                              "rotation_dt", seats.rotation_dt, true));
  }
  return out;
}

// [model.excitation]: the two records with their own factors, and the shared options.
struct ExcitationRecords {
  std::optional<Record> longitudinal, transverse;
  double longitudinal_factor = 1.0, transverse_factor = 1.0;  // amplitude factors
  GroundMotionOptions options;                                // time scale, baseline
  ScaleTo scale_to = ScaleTo::kPga;
  double sa_period = 0.0;    // [s] of the reported (and, for "sa", the target) PSA; 0: the
                             //   bridge's first natural period, found once the bridge is built
  double sa_damping = 0.05;  // zeta of the reported PSA
};

// The factor that scales record r to target [g]; fails at key when the record is all zeros,
// or so weak that the factor, times scale, overflows.
double factor_to(const Section& s, const std::string& key, const Record& r, double target,
                 double scale) {
  const double pk = peak(r);
  if (!(pk > 0)) s.fail(key, "the record's peak acceleration is zero: cannot scale it");
  const double factor = target * kStandardGravity / pk;
  if (!std::isfinite(factor * scale)) {
    s.fail(key, "the record's peak acceleration " + six_digits(pk) +
                    " m/s^2 is too small to scale to " + six_digits(target) + " g" +
                    (scale != 1.0 ? " with scale = " + six_digits(scale) : std::string()) +
                    ": the factor overflows");
  }
  return factor;
}

// target_pga scales the transverse component (or the longitudinal one when it is alone);
// without longitudinal_pga the other component takes the same factor. longitudinal_pga gives
// the longitudinal component its own target (docs/bridge.md, "Target PGAs").
void scale_to_targets(const Section& s, const ExcitationSettings& e, ExcitationRecords& out) {
  const Record* ref = out.transverse ? &*out.transverse
                                     : (out.longitudinal ? &*out.longitudinal : nullptr);
  double common = 1.0;
  if (ref != nullptr && e.target_pga > 0) {
    common = factor_to(s, "target_pga", *ref, e.target_pga, e.scale);
  }
  out.transverse_factor = e.scale * common;
  out.longitudinal_factor = e.scale * common;
  if (e.longitudinal_pga > 0) {
    if (!out.longitudinal) s.fail("longitudinal_pga", "needs a longitudinal_record to scale");
    out.longitudinal_factor =
        e.scale *
        factor_to(s, "longitudinal_pga", *out.longitudinal, e.longitudinal_pga, e.scale);
  }
}

// The first (longest) natural period [s] of a bridge, built on demand: scale_to = "sa" needs
// it before the bridge with its support motions exists.
using FirstPeriod = std::function<double()>;

// The factor that scales record r to a PSA of target [g] at out.sa_period; fails at key when
// the record's PSA there is zero.
double factor_to_sa(const Section& s, const std::string& key, const Record& r, double target,
                    const ExcitationRecords& out, double scale) {
  const double sa = spectral_acceleration_g(time_scaled(r, out.options.time_scale), out.sa_period,
                                            out.sa_damping);
  if (!(sa > 0)) {
    s.fail(key, "the record's spectral acceleration at sa_period = " +
                    config::format_value(out.sa_period) + " s is zero: cannot scale it");
  }
  if (!std::isfinite(target / sa * scale)) {
    s.fail(key, "the record's spectral acceleration " + six_digits(sa) +
                    " g at sa_period is too small to scale to " + six_digits(target) +
                    " g: the factor overflows");
  }
  return target / sa;
}

// scale_to = "sa": target_sa scales the transverse component (or the longitudinal one when it
// is alone) to PSA(sa_period, sa_damping), in place of target_pga; the other component takes
// the same factor unless longitudinal_pga or longitudinal_sa gives it its own target
// (docs/bridge.md, "Target spectral accelerations").
void scale_to_spectra(const Section& s, const ExcitationSettings& e,
                      const FirstPeriod& first_period, ExcitationRecords& out) {
  const Record* ref = out.transverse ? &*out.transverse
                                     : (out.longitudinal ? &*out.longitudinal : nullptr);
  if (ref == nullptr) s.fail("scale_to", "\"sa\" needs a transverse_record or longitudinal_record");
  if (e.longitudinal_pga > 0 && e.longitudinal_sa > 0) {
    s.fail("longitudinal_sa", "give longitudinal_pga or longitudinal_sa, not both");
  }
  out.sa_period = s.has("sa_period") ? e.sa_period : first_period();
  if (!(std::isfinite(out.sa_period) && out.sa_period > 0)) {
    s.fail("sa_period", "the bridge has no finite first natural period; give sa_period (> 0 s)");
  }
  double common = 1.0;
  if (e.target_sa > 0) common = factor_to_sa(s, "target_sa", *ref, e.target_sa, out, e.scale);
  out.transverse_factor = e.scale * common;
  out.longitudinal_factor = e.scale * common;
  if (e.longitudinal_pga > 0) {
    if (!out.longitudinal) s.fail("longitudinal_pga", "needs a longitudinal_record to scale");
    out.longitudinal_factor =
        e.scale *
        factor_to(s, "longitudinal_pga", *out.longitudinal, e.longitudinal_pga, e.scale);
  }
  if (e.longitudinal_sa > 0) {
    if (!out.longitudinal) s.fail("longitudinal_sa", "needs a longitudinal_record to scale");
    out.longitudinal_factor =
        e.scale *
        factor_to_sa(s, "longitudinal_sa", *out.longitudinal, e.longitudinal_sa, out, e.scale);
  }
}

// The scaling of each component as summary.json reports it, at out.sa_period or else the
// built bridge's first natural period.
InputMotion describe_excitation(const ExcitationRecords& e, integrators::System& bridge) {
  double period = e.sa_period;
  if (period == 0.0) {
    const std::vector<double> periods = integrators::natural_periods(bridge);
    period = periods.empty() ? NAN : periods.front();
  }
  const auto describe = [&](const Record& r, double factor) {
    if (!(std::isfinite(period) && period > 0)) {
      InputComponent c;
      c.pga_g = std::abs(factor) * peak_acceleration_g(r);
      c.sa_g = c.sa_period = NAN;
      c.sa_damping = e.sa_damping;
      c.scale_factor = factor;
      return c;
    }
    return describe_input(time_scaled(r, e.options.time_scale), factor, period, e.sa_damping);
  };
  InputMotion in;
  if (e.transverse) in.transverse = describe(*e.transverse, e.transverse_factor);
  if (e.longitudinal) in.longitudinal = describe(*e.longitudinal, e.longitudinal_factor);
  return in;
}

// time_scale keeps the sample times of record r finite and strictly increasing (a huge or
// tiny factor can make them overflow or round onto each other).
void check_time_scale(const Section& s, const Record& r, double time_scale) {
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    const double t = time_scale * r.t[i];
    const double before = i > 0 ? time_scale * r.t[i - 1] : 0.0;
    if (!std::isfinite(t) || (i > 0 && !(t > before))) {
      s.fail("time_scale", "= " + io::three_digits(time_scale) + " makes the sample times of "
                           "record \"" + r.source + "\" " +
                           (std::isfinite(t) ? "coincide (samples " + std::to_string(i) + " and " +
                                                   std::to_string(i + 1) + ")"
                                             : "infinite (sample " + std::to_string(i + 1) + ")"));
    }
  }
}

// The records of one excitation (the single [model.excitation], or one entry of a sequence,
// read from section s with its settings e): read, checked against the shared time scale, and
// scaled.
ExcitationRecords read_records(const Section& s, const ExcitationSettings& e,
                               const FirstPeriod& first_period, const SeatMotions& seats,
                               double time_scale, bool baseline_correction) {
  ExcitationRecords out;
  const RecordKeys keys =
      record_keys(s, "record_unit", e.record_unit, "record_dt", e.record_dt, false);
  if (!e.longitudinal_record.empty()) {
    out.longitudinal = read_record(s, "longitudinal_record", e.longitudinal_record, keys);
  }
  if (!e.transverse_record.empty()) {
    out.transverse = read_record(s, "transverse_record", e.transverse_record, keys);
  }
  for (const std::optional<Record>* r : std::array<const std::optional<Record>*, 4>{
           &out.longitudinal, &out.transverse, &seats.rotation[0], &seats.rotation[1]}) {
    if (*r) check_time_scale(s, **r, time_scale);
  }
  out.options.time_scale = time_scale;
  out.options.baseline_correction = baseline_correction;
  out.scale_to = e.scale_to;
  out.sa_damping = e.sa_damping;
  if (e.scale_to == ScaleTo::kSa) {
    scale_to_spectra(s, e, first_period, out);
  } else {
    if (s.has("target_sa") || s.has("longitudinal_sa")) {
      s.fail(s.has("target_sa") ? "target_sa" : "longitudinal_sa", "needs scale_to = \"sa\"");
    }
    if (s.has("sa_period")) out.sa_period = e.sa_period;
    if (!out.longitudinal && !out.transverse) {
      // An amplitude with nothing to scale would run the scene without ground motion.
      for (const char* key : {"target_pga", "longitudinal_pga", "scale"}) {
        if (s.has(key)) {
          s.fail(key, "needs a record to scale: give longitudinal_record or transverse_record "
                      "in [" + s.path() + "], or remove " + std::string(key));
        }
      }
    }
    scale_to_targets(s, e, out);
  }
  out.options.target_pga = 0.0;
  return out;
}

// [model.excitation]: one excitation, or a sequence of them with a rest after each.
struct Excitation {
  std::vector<ExcitationRecords> records;  // none without [model.excitation]; one; or the
                                           //   sequence's, in order
  std::vector<double> rest;                // [s] after each record (0 for a single one)
  bool sequence = false;
  bool baseline_correction = true;
};

// [[model.excitation.sequence]]: its entries, each with the record keys of [model.excitation]
// but the shared time_scale and baseline_correction, and its rest.
void read_sequence(const Section& s, const ExcitationSettings& shared,
                   const FirstPeriod& first_period, const SeatMotions& seats, Excitation& out) {
  for (const auto& f : ExcitationSettings::fields()) {
    const bool is_shared = std::find(kSequenceSharedKeys.begin(), kSequenceSharedKeys.end(),
                                     f.key) != kSequenceSharedKeys.end();
    if (!is_shared && s.has(f.key)) {
      s.fail(f.key, "belongs to each [[" + s.key_path("sequence") +
                        "]] entry when the excitation is a sequence: give the records either "
                        "in [" + s.path() + "] or in its sequence, not both");
    }
  }
  const toml::node* node = s.table().get("sequence");
  if (const toml::array* a = node->as_array(); a != nullptr && a->empty()) {
    s.fail("sequence", "is empty: give one [[" + s.key_path("sequence") +
                           "]] entry per record, in order");
  }
  const toml::array* entries = s.array_of_tables("sequence");
  std::vector<std::string_view> keys;
  for (const auto& f : ExcitationSettings::fields()) {
    if (std::find(kSequenceSharedKeys.begin(), kSequenceSharedKeys.end(), f.key) ==
        kSequenceSharedKeys.end()) {
      keys.push_back(f.key);
    }
  }
  for (const auto& k : keys_of(SequenceSettings::fields())) keys.push_back(k);
  for (std::size_t k = 0; k < entries->size(); ++k) {
    Section entry(s.context(), *(*entries)[k].as_table(),
                  s.key_path("sequence") + "[" + std::to_string(k) + "]");
    for (const std::string_view key : kSequenceSharedKeys) {
      if (entry.has(key)) {
        entry.fail(key, "is shared by the records of a sequence: give it in [" + s.path() + "]");
      }
    }
    entry.only(keys);
    ExcitationSettings e;
    entry.read_all(ExcitationSettings::fields(), e);
    SequenceSettings r;
    entry.read_all(SequenceSettings::fields(), r);
    if (e.longitudinal_record.empty() && e.transverse_record.empty()) {
      entry.fail_table("names no record: give longitudinal_record or transverse_record");
    }
    out.records.push_back(read_records(entry, e, first_period, seats, shared.time_scale,
                                       shared.baseline_correction));
    out.rest.push_back(r.rest);
  }
}

Excitation read_excitation(const Section& m, const FirstPeriod& first_period,
                           const SeatMotions& seats, double& time_scale) {
  Excitation out;
  ExcitationSettings e;
  const auto* t = m.subtable("excitation");
  if (t == nullptr) return out;
  Section s(m.context(), *t, m.key_path("excitation"));
  std::vector<std::string_view> keys = keys_of(ExcitationSettings::fields());
  keys.push_back("sequence");
  s.only(keys);
  s.read_all(ExcitationSettings::fields(), e);
  time_scale = e.time_scale;
  out.baseline_correction = e.baseline_correction;
  if (s.has("sequence")) {
    out.sequence = true;
    read_sequence(s, e, first_period, seats, out);
    return out;
  }
  out.records.push_back(
      read_records(s, e, first_period, seats, e.time_scale, e.baseline_correction));
  out.rest.push_back(0.0);
  return out;
}

// The end of a record pair's samples after time scaling [s] (the later component's).
double records_end(const ExcitationRecords& e) {
  double end = 0.0;
  for (const std::optional<Record>* r : {&e.longitudinal, &e.transverse}) {
    if (*r) end = std::max(end, e.options.time_scale * (*r)->t.back());
  }
  return end;
}

// The motions of one direction of an excitation at each delay: of its one record, or of its
// sequence, each record delayed by its place in the sequence (models::GroundMotion::sequence),
// one object per distinct delay (shared by the supports).
class SequenceSet {
 public:
  SequenceSet(const Excitation& e, std::optional<Record> ExcitationRecords::* record,
              double ExcitationRecords::* factor)
      : ends_at_rest_(e.baseline_correction) {
    double offset = 0.0;  // the time origin of record k in the sequence [s]
    for (std::size_t k = 0; k < e.records.size(); ++k) {
      const ExcitationRecords& r = e.records[k];
      GroundMotionOptions o = r.options;
      o.scale = r.*factor;
      sets_.emplace_back(r.*record, o, offset);
      offset += records_end(r) + e.rest[k];
    }
  }
  parts::Motion at_delay(double delay) {
    if (sets_.size() == 1) return sets_.front().at_delay(delay);
    auto& m = cache_[delay];
    if (!m) {
      std::vector<GroundMotion> parts;
      for (MotionSet& set : sets_) {
        if (const parts::Motion part = set.at_delay(delay)) parts.push_back(*part);
      }
      if (parts.empty()) return nullptr;
      m = std::make_shared<const GroundMotion>(GroundMotion::sequence(parts, ends_at_rest_));
    }
    return m;
  }

 private:
  std::vector<MotionSet> sets_;
  bool ends_at_rest_ = true;
  std::map<double, parts::Motion> cache_;
};

// The support motions of every bent and seat, and the end of the longest bent motion [s]
// (of a sequence, with the rest after its last record). ground: the zero-delay motions (x, y)
// of the connectors to the ground.
BridgeDesign::Excitation support_motions(const Excitation& e, const SeatMotions& seats,
                                         const std::vector<double>& bent_delays, double& end,
                                         std::array<parts::Motion, 2>& ground) {
  BridgeDesign::Excitation exc;
  end = 0.0;
  if (e.records.empty()) {
    for (std::size_t j = 0; j < bent_delays.size(); ++j) exc.bents.push_back({});
    ground = {nullptr, nullptr};
  }
  ExcitationRecords none;
  const ExcitationRecords& first = e.records.empty() ? none : e.records.front();
  SequenceSet mx(e, &ExcitationRecords::longitudinal, &ExcitationRecords::longitudinal_factor);
  SequenceSet my(e, &ExcitationRecords::transverse, &ExcitationRecords::transverse_factor);
  GroundMotionOptions rot = first.options;
  rot.scale = seats.rotation_scale;
  if (!e.records.empty()) {
    ground = {mx.at_delay(0.0), my.at_delay(0.0)};
    for (double delay : bent_delays) {
      exc.bents.push_back({mx.at_delay(delay), my.at_delay(delay), nullptr});
    }
  }
  for (std::size_t a = 0; a < 2; ++a) {
    if (!e.records.empty()) {
      exc.seats[a].longitudinal = mx.at_delay(seats.delays[a]);
      if (seats.transverse) exc.seats[a].transverse = my.at_delay(seats.delays[a]);
    }
    if (seats.rotation[a]) {
      GroundMotionOptions o = rot;
      o.delay = seats.delays[a];
      exc.seats[a].rotation = std::make_shared<const GroundMotion>(*seats.rotation[a], o);
    }
  }
  for (const auto& b : exc.bents) {
    for (const auto& mo : {b.longitudinal, b.transverse}) {
      if (mo) end = std::max(end, mo->end_time());
    }
  }
  if (e.sequence && end > 0) end += e.rest.back();
  return exc;
}

// [[model.segments]] and [[model.hinges]] with [model] skew_deg; or the one segment of
// [model.deck], which must not be given with them.
SegmentedDeck read_segments(const Section& m, BridgeDesign& p) {
  if (m.has("deck")) {
    m.fail("deck", "give either [model.deck] (one segment) or [[model.segments]], not both");
  }
  LayoutSettings layout;
  m.read_all(LayoutSettings::fields(), layout);
  p.deck.skew_deg = layout.skew_deg;
  SegmentedDeck d;
  d.segments = read_bodies(m, "segments");
  d.hinges = read_joints(m, "hinges", d.segments.size() - 1,
                         "one between each two neighbouring segments",
                         {"seat_length", "restrainer", "skew_deg"});
  // Each hinge's own angle, where it gives one.
  const auto* hinges = m.array_of_tables("hinges");
  for (std::size_t k = 0; hinges != nullptr && k < hinges->size(); ++k) {
    const Section h(m.context(), *(*hinges)[k].as_table(),
                    m.key_path("hinges") + "[" + std::to_string(k) + "]");
    d.hinge_skews_deg.emplace_back();
    if (!h.has("skew_deg")) continue;
    HingeSkewSettings hs;
    h.read_all(HingeSkewSettings::fields(), hs);
    d.hinge_skews_deg.back() = hs.skew_deg;
  }
  return d;
}

// [model.deck]: the one deck, straight or curved (radius with length or angle_deg); a curved
// deck without inertia gets its annular sector's, I = m I_G / m (models/deck_geometry.hpp).
std::optional<Section> read_deck(const Section& m, BridgeDesign& p) {
  const auto* t = m.subtable("deck");
  if (t == nullptr) return std::nullopt;
  Section s(m.context(), *t, m.key_path("deck"));
  std::vector<std::string_view> keys = keys_of(bridge_deck_fields());
  for (const auto& k : keys_of(CurvedDeckSettings::fields())) keys.push_back(k);
  s.only(keys);
  s.read_all(bridge_deck_fields(), p);
  if (s.has("angle_deg")) {
    if (!s.has("radius")) s.fail("angle_deg", "needs radius (a curved deck's R [m])");
    if (s.has("length")) {
      s.fail("angle_deg", "give either length (the arc length) or angle_deg, not both");
    }
    CurvedDeckSettings c;
    s.read_all(CurvedDeckSettings::fields(), c);
    p.deck.length = p.deck.radius * c.angle_deg * std::numbers::pi / 180.0;
  }
  if (p.deck.curved()) {
    try {
      p.deck.validate();
      if (!s.has("inertia")) {
        p.inertia = p.mass * annular_sector(p.deck.radius, p.deck.width,
                                            p.deck.subtended_angle()).inertia_per_mass;
      }
    } catch (const std::invalid_argument& e) {
      s.rethrow(e);
    }
  }
  return s;
}

// [model.abutments] skew_left_deg / skew_right_deg: each abutment's own angle.
void read_abutment_skews(const Section& m, BridgeDesign& p) {
  const auto* t = m.subtable("abutments");
  if (t == nullptr) return;
  const Section s(m.context(), *t, m.key_path("abutments"));
  AbutmentSkewSettings a;
  s.read_all(AbutmentSkewSettings::fields(), a);
  if (s.has("skew_left_deg")) p.deck.skew_left_deg = a.skew_left_deg;
  if (s.has("skew_right_deg")) p.deck.skew_right_deg = a.skew_right_deg;
  if ((s.has("skew_left_deg") || s.has("skew_right_deg")) && p.deck.curved()) {
    s.fail(s.has("skew_left_deg") ? "skew_left_deg" : "skew_right_deg",
           "a curved deck's abutment faces are radial ([model.deck] radius)");
  }
}

// A seat shorter than its joint's opening at t0 (models/assembly_limits.cpp): reported at the
// seat's key (seat_length of [model.abutments] or of the hinge) with the gap that conflicts
// with it, and the likely unit when the gap is longer than the seat but not in mm.
[[noreturn]] void seat_error(const Section& m, const std::string& joint, const BridgeDesign& p,
                             const SegmentedDeck* d, const BridgeLimits& limits,
                             const std::string& detail) {
  double seat = limits.abutment_seat;
  double gap = joint == "left" ? p.deck.gap_left : p.deck.gap_right;
  std::string gap_key = std::string("[model.gaps] ") + (joint == "left" ? "left" : "right");
  std::optional<Section> at;
  if (joint.rfind("hinge_", 0) == 0) {
    const std::size_t k = std::stoul(joint.substr(6)) - 1;
    const auto* hinges = m.array_of_tables("hinges");
    if (hinges != nullptr && k < hinges->size() && d != nullptr && k < d->hinges.size()) {
      at.emplace(m.context(), *(*hinges)[k].as_table(),
                 m.key_path("hinges") + "[" + std::to_string(k) + "]");
      gap = d->hinges[k].gap;
      gap_key = "gap";
      seat = k < limits.hinge_seats.size() ? limits.hinge_seats[k] : seat;
    }
  } else if (const auto* t = m.subtable("abutments")) {
    at.emplace(m.context(), *t, m.key_path("abutments"));
  }
  if (!at) m.fail_table("seat_length: " + detail);
  // detail: "seat_length is shorter than the joint's opening at t0 (overlap -0.01 m); ..."
  const auto open = detail.find("(overlap ");
  const std::string overlap =
      open == std::string::npos ? "" : " " + detail.substr(open, detail.find(')', open) - open + 1);
  std::string what = "seat_length " + six_digits(seat) + " m is shorter than the " + joint +
                     " joint's opening at t0" + overlap + ", set by " + gap_key + " = " +
                     six_digits(gap) + " m and the deck's initial position; it must exceed it";
  if (gap > seat && gap / 1000.0 < seat) {
    what += "; a gap in mm? " + six_digits(gap) + " mm is " + six_digits(gap / 1000.0) + " m";
  }
  at->fail("seat_length", what);
}

// What a bridge adds to the benchmark's parts: the part kinds' parts, limit states.
struct BridgeAdditions {
  BridgePartSettings parts;
  BridgeLimitKeys limits;
};

// The bridge as an assembly of parts (models/bridge_parts.hpp), one deck (d == nullptr) or
// segmented, with the additions: the parts of every kind (scene/bridge_part_kinds.hpp) on the
// ground motions g, then the limit states watched on its segments (docs/scenes.md: a bridge in
// segments always watches its joints' closure; one deck only the limit states its scene asks
// for).
std::unique_ptr<integrators::System> assemble(const Section& m, const BridgeDesign& p,
                                              const SegmentedDeck* d, const BridgeAdditions& a,
                                              const std::array<parts::Motion, 2>& g) {
  try {
    Assembly::Parts parts = d != nullptr ? bridge_parts(p, *d) : bridge_parts(p);
    const std::size_t deck_bodies = parts.bodies.size();
    if (a.parts.any()) {
      PartSite site{.design = p, .hinge_gaps = {}, .ground = g, .deck_bodies = deck_bodies};
      if (d != nullptr) {
        for (const auto& h : d->hinges) site.hinge_gaps.push_back(h.gap);
      }
      add_bridge_parts(a.parts, site, parts);
    }
    if (d != nullptr || a.limits.requested) {
      parts.limits = bridge_limit_spec(a.limits.limits, deck_bodies);
    }
    return std::make_unique<Assembly>(std::move(parts));
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    const std::string unseating = "limits.unseating_";
    if (what.rfind(unseating, 0) == 0) {
      const std::string joint = what.substr(unseating.size(), what.find(':') - unseating.size());
      seat_error(m, joint, p, d, a.limits.limits, what.substr(what.find(": ") + 2));
    }
    if (d != nullptr) rethrow_penetration(m, "segments", "hinges", e);
    m.rethrow(e);
  }
}

// The bridge of [[model.segments]]: an assembly of parts.
std::unique_ptr<integrators::System> segmented_bridge(const Section& m, BridgeDesign& p,
                                                      SegmentedDeck& d, const BentsRead& bents,
                                                      const BridgeAdditions& a,
                                                      const std::array<parts::Motion, 2>& g) {
  d.bent_segment = bents.segments;
  for (std::size_t i = 0; i < d.segments.size(); ++i) {
    if (!torsionally_restrained(p.bents, d.bent_segment, static_cast<int>(i))) {
      m.fail("bents", "segment " + std::to_string(i) + " " + kTwoBents);
    }
  }
  return assemble(m, p, &d, a, g);
}

}  // namespace

BridgeScene build_bridge(Section& m) {
  std::vector<std::string_view> keys{"kind", "skew_deg", "deck",  "segments", "hinges",
                                     "gaps", "damping",  "bents", "seats",    "excitation"};
  for (const auto& kind : bridge_part_kinds()) {
    if (!kind.key.empty()) keys.push_back(kind.key);
  }
  keys.push_back("limit_states");
  m.only(keys);
  const bool segmented = m.has("segments");
  if (!segmented) {
    for (const char* key : {"skew_deg", "hinges"}) {
      if (m.has(key)) m.fail(key, "belongs to a bridge in [[model.segments]]");
    }
  }
  BridgeDesign p = BridgeDesign::benchmark();
  p.bents.clear();
  SegmentedDeck segments;
  if (segmented) segments = read_segments(m, p);
  const std::optional<Section> deck = segmented ? std::nullopt : read_deck(m, p);
  read_abutment_skews(m, p);
  if (deck) check_body(*deck, p.mass, p.inertia, p.deck.length, p.deck.width);
  std::vector<double> lengths;
  for (const auto& b : segments.segments) lengths.push_back(b.length);
  if (!segmented) lengths.push_back(p.deck.length);
  read_table(m, "gaps", bridge_gap_fields(), p);
  read_damping(m, p);
  BridgeAdditions add;
  add.limits = read_bridge_limits(m);
  const Section* arc = deck && p.deck.curved() && deck->has("angle_deg") ? &*deck : nullptr;
  const BentsRead bents = read_bents(m, lengths, p, add.limits.limits.drift_ratio > 0, arc);
  add.limits.limits.bent_heights = bents.heights;
  const SeatMotions seats = read_seats(m, p);
  add.parts = read_bridge_parts(m, PartShape{lengths, p.deck});
  // The connectors and keys stand on a straight deck's axis and faces (docs/bridge.md,
  // "Curved decks").
  if (p.deck.curved() && add.parts.any()) {
    deck->fail("radius", "a curved deck takes bents and seats only: no bearings, restrainers, "
                         "shear keys or backfill yet");
  }
  BridgeScene out;
  std::array<parts::Motion, 2> ground{};
  // The system for a set of support motions: one deck, segmented, with the additions.
  const auto make = [&](BridgeDesign::Excitation exc) -> std::unique_ptr<integrators::System> {
    p.excitation = std::move(exc);
    if (segmented) return segmented_bridge(m, p, segments, bents, add, ground);
    if (deck) {
      // The deck's own errors (an initial penetration) at its key in [model.deck].
      try {
        p.validate();
      } catch (const std::invalid_argument& e) {
        if (std::string(e.what()).rfind("initial_position", 0) == 0) deck->rethrow(e);
      }
    }
    return assemble(m, p, nullptr, add, ground);
  };
  const FirstPeriod first_period = [&] {
    const std::vector<double> periods = integrators::natural_periods(*make({}));
    return periods.empty() ? NAN : periods.front();
  };
  const Excitation excitation = read_excitation(m, first_period, seats, out.time_scale);
  // A record whose motion cannot be built (its velocity or displacement overflows) is
  // reported at [model.excitation], the table that names the records and their time scale.
  BridgeDesign::Excitation motions;
  try {
    motions = support_motions(excitation, seats, bents.delays, out.motion_end, ground);
  } catch (const std::invalid_argument& e) {
    m.fail(m.has("excitation") ? "excitation" : "seats", e.what());
  }
  out.system = make(std::move(motions));
  // A sequence reports its last record: the aftershock a sequence study varies.
  if (!excitation.records.empty()) {
    out.input = describe_excitation(excitation.records.back(), *out.system);
  }
  if (!segmented) out.design = p;
  return out;
}

}  // namespace nsb::scene
