#include "models/scene.hpp"

#include "integrators/compliance.hpp"
#include "lcp/solve.hpp"
#include "models/bridge.hpp"
#include "models/ground_motion.hpp"
#include "models/rigid_deck.hpp"
#include "models/simple_systems.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

namespace nsb::models {

namespace {

namespace fs = std::filesystem;

constexpr double kStandardGravity = 9.81;  // [m/s^2]: target PGA in scenes is in units of g

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Where errors point: the file, and for each key either its source position or "(override)".
struct Context {
  std::string file;
  fs::path dir;
  std::set<std::string> overridden;  // key paths set by overrides, e.g. "model.bents[0].height"
  mutable double record_step = 0.0;  // shortest sampling interval of the records read, before
                                     //   time scaling [s]; 0 when no record was read

  [[noreturn]] void fail(const toml::node* n, const std::string& key,
                         const std::string& what) const {
    std::ostringstream s;
    s << file;
    if (overridden.count(key) != 0) {
      s << ": " << key << " (override)";
    } else if (n != nullptr && n->source().begin.line > 0) {
      s << ':' << n->source().begin.line << ':' << n->source().begin.column << ": " << key;
    } else {
      s << ": " << key;
    }
    s << ": " << what;
    throw std::invalid_argument(s.str());
  }
};

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date/time";
  }
}

// One TOML table of the schema: typed reads with defaults, and the check for unknown keys.
class Section {
 public:
  Section(const Context& c, const toml::table& t, std::string path)
      : c_(c), t_(t), path_(std::move(path)) {}

  const std::string& path() const { return path_; }
  std::string key_path(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }
  bool has(const std::string& key) const { return t_.get(key) != nullptr; }
  const toml::node* node(const std::string& key) const { return t_.get(key); }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    const toml::node* n = t_.get(key);
    c_.fail(n != nullptr ? n : &t_, key_path(key), what);
  }
  [[noreturn]] void fail_table(const std::string& what) const { c_.fail(&t_, path_, what); }

  // A finite number (integer or float); `ok` checks the range, `allowed` describes it.
  double number(const std::string& key, double def,
                const std::function<bool(double)>& ok = nullptr, const std::string& allowed = "") {
    const auto v = opt_number(key, ok, allowed);
    return v ? *v : def;
  }
  std::optional<double> opt_number(const std::string& key,
                                   const std::function<bool(double)>& ok = nullptr,
                                   const std::string& allowed = "") {
    used_.insert(key);
    const toml::node* n = t_.get(key);
    if (n == nullptr) return std::nullopt;
    double v = 0.0;
    if (n->is_integer()) {
      v = static_cast<double>(n->as_integer()->get());
    } else if (n->is_floating_point()) {
      v = n->as_floating_point()->get();
    } else {
      fail(key, "expected a number, got " + type_name(*n));
    }
    if (!std::isfinite(v)) fail(key, "must be finite");
    if (ok && !ok(v)) fail(key, allowed + " (got " + fmt(v) + ")");
    return v;
  }
  int integer(const std::string& key, int def, int lo, int hi) {
    used_.insert(key);
    const toml::node* n = t_.get(key);
    if (n == nullptr) return def;
    if (!n->is_integer()) fail(key, "expected an integer, got " + type_name(*n));
    const auto v = n->as_integer()->get();
    if (v < lo || v > hi) {
      fail(key, "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                    "] (got " + std::to_string(v) + ")");
    }
    return static_cast<int>(v);
  }
  bool boolean(const std::string& key, bool def) {
    used_.insert(key);
    const toml::node* n = t_.get(key);
    if (n == nullptr) return def;
    if (!n->is_boolean()) fail(key, "expected true or false, got " + type_name(*n));
    return n->as_boolean()->get();
  }
  std::optional<std::string> opt_string(const std::string& key) {
    used_.insert(key);
    const toml::node* n = t_.get(key);
    if (n == nullptr) return std::nullopt;
    if (!n->is_string()) fail(key, "expected a string, got " + type_name(*n));
    return n->as_string()->get();
  }
  std::string choice(const std::string& key, const std::string& def,
                     const std::vector<std::string>& allowed) {
    const auto v = opt_string(key).value_or(def);
    if (std::find(allowed.begin(), allowed.end(), v) == allowed.end()) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
      fail(key, "must be one of " + list + " (got \"" + v + "\")");
    }
    return v;
  }
  Eigen::Vector3d vec3(const std::string& key, const Eigen::Vector3d& def) {
    used_.insert(key);
    const toml::node* n = t_.get(key);
    if (n == nullptr) return def;
    const toml::array* a = n->as_array();
    if (a == nullptr || a->size() != 3) fail(key, "expected an array of 3 numbers");
    Eigen::Vector3d v;
    for (std::size_t i = 0; i < 3; ++i) {
      const toml::node& e = (*a)[i];
      if (e.is_integer()) {
        v(static_cast<int>(i)) = static_cast<double>(e.as_integer()->get());
      } else if (e.is_floating_point()) {
        v(static_cast<int>(i)) = e.as_floating_point()->get();
      } else {
        fail(key, "expected an array of 3 numbers, element " + std::to_string(i) + " is " +
                      type_name(e));
      }
    }
    if (!v.allFinite()) fail(key, "must be finite");
    return v;
  }
  const toml::table* table(const std::string& key) {
    used_.insert(key);
    const toml::node* n = t_.get(key);
    if (n == nullptr) return nullptr;
    if (!n->is_table()) fail(key, "expected a table, got " + type_name(*n));
    return n->as_table();
  }
  const toml::array* array_of_tables(const std::string& key) {
    used_.insert(key);
    const toml::node* n = t_.get(key);
    if (n == nullptr) return nullptr;
    if (!n->is_array_of_tables()) fail(key, "expected an array of tables ([[" + key_path(key) + "]])");
    return n->as_array();
  }
  // Rejects unknown keys before any value is checked, so that a typo is reported as such
  // rather than as a missing key.
  void only(const std::vector<std::string>& known) {
    for (auto&& [k, v] : t_) {
      const std::string key(k.str());
      if (std::find(known.begin(), known.end(), key) == known.end()) {
        std::string list;
        for (const auto& u : known) list += (list.empty() ? "" : ", ") + u;
        c_.fail(&v, key_path(key), "unknown key; allowed here: " + list);
      }
    }
  }
  // Every key of the table must have been read: anything else is unknown (a typo).
  void finish(const std::vector<std::string>& known_hint = {}) const {
    for (auto&& [k, v] : t_) {
      const std::string key(k.str());
      if (used_.count(key) == 0) {
        std::string list;
        for (const auto& u : known_hint.empty() ? std::vector<std::string>(used_.begin(), used_.end())
                                                : known_hint) {
          list += (list.empty() ? "" : ", ") + u;
        }
        c_.fail(&v, key_path(key), "unknown key; allowed here: " + list);
      }
    }
  }

  // Rethrows a model's validation error "field: what" at the key `field` when it is one of
  // this table's keys, else at the table.
  [[noreturn]] void rethrow(const std::invalid_argument& e,
                            const std::map<std::string, std::string>& field_to_key = {}) const {
    const std::string msg = e.what();
    const auto colon = msg.find(": ");
    if (colon != std::string::npos) {
      std::string field = msg.substr(0, colon);
      const std::string what = msg.substr(colon + 2);
      if (const auto it = field_to_key.find(field); it != field_to_key.end()) field = it->second;
      if (t_.get(field) != nullptr || used_.count(field) != 0) fail(field, what);
    }
    fail_table(msg);
  }

 private:
  const Context& c_;
  const toml::table& t_;
  std::string path_;
  std::set<std::string> used_;
};

bool positive(double v) { return v > 0; }
bool non_negative(double v) { return v >= 0; }
bool unit_interval(double v) { return v >= 0 && v <= 1; }

// ---------------------------------------------------------------------------------------------
// Overrides

std::string strip(std::string s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

bool is_index(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char ch) { return std::isdigit(ch); });
}

void apply_override(toml::table& root, const std::string& text, Context& ctx) {
  const auto eq = text.find('=');
  if (eq == std::string::npos) {
    throw std::invalid_argument(ctx.file + ": override \"" + text +
                                "\": expected section.key=value");
  }
  const std::string lhs = strip(text.substr(0, eq));
  const std::string rhs = strip(text.substr(eq + 1));
  std::vector<std::string> parts;
  std::stringstream ss(lhs);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(strip(p));
  if (parts.size() < 2 || std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); })) {
    throw std::invalid_argument(ctx.file + ": override \"" + text +
                                "\": expected section.key=value");
  }
  // The value: a TOML value, or else the raw text as a string.
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + rhs);
  } catch (const toml::parse_error&) {
    parsed = toml::table{};
    parsed.insert("v", rhs);
  }
  toml::node* value = parsed.get("v");

  // Walk to the parent of the last component; tables are created, arrays indexed.
  std::string path;
  toml::node* cur = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& p = parts[i];
    if (auto* t = cur->as_table()) {
      path += (path.empty() ? "" : ".") + p;
      toml::node* next = t->get(p);
      if (next == nullptr) {
        t->insert(p, toml::table{});
        next = t->get(p);
      }
      cur = next;
    } else if (auto* a = cur->as_array(); a != nullptr && is_index(p)) {
      // Any run of digits is an index; one too large for size_t is out of range like any
      // other index past the end.
      std::size_t k = 0;
      const auto [end, ec] = std::from_chars(p.data(), p.data() + p.size(), k);
      if (ec != std::errc() || end != p.data() + p.size() || k >= a->size()) {
        throw std::invalid_argument(ctx.file + ": override \"" + text + "\": " + path + "." +
                                    p + ": index out of range; " + path + " has " +
                                    std::to_string(a->size()) + " elements (0-based)");
      }
      path += "[" + p + "]";
      cur = a->get(k);
    } else {
      throw std::invalid_argument(ctx.file + ": override \"" + text + "\": " + path +
                                  " is not a table");
    }
  }
  const std::string& last = parts.back();
  auto* parent = cur->as_table();
  if (parent == nullptr) {
    throw std::invalid_argument(ctx.file + ": override \"" + text + "\": " + path +
                                " is not a table");
  }
  value->visit([&](auto& v) { parent->insert_or_assign(last, std::move(v)); });
  ctx.overridden.insert(path + "." + last);
}

// ---------------------------------------------------------------------------------------------
// Settings

void read_solver(Section s, SolverSettings& out) {
  s.only({"method", "end_time", "step", "theta", "tolerance", "lcp_solver", "stiffness_factor",
          "contact_stiffness", "damping_law", "stick_slip_velocity"});
  SolverSettings d;
  out.method = s.choice("method", d.method, {"moreau", "event_driven", "compliance"});
  out.end_time = s.number("end_time", out.end_time, positive, "must be > 0 [s]");
  out.step = s.number("step", d.step, positive, "must be > 0 [s]");
  if (out.step > out.end_time) s.fail("step", "must be <= end_time (" + fmt(out.end_time) + " s)");
  out.theta = s.number("theta", d.theta, [](double v) { return v >= 0.5 && v <= 1.0; },
                       "must be in [0.5, 1]");
  out.tolerance = s.number("tolerance", d.tolerance, [](double v) { return v > 0 && v < 1; },
                           "must be in (0, 1)");
  out.lcp_solver = s.choice("lcp_solver", d.lcp_solver, {"lemke", "pgs", "nfb", "enum"});
  out.stiffness_factor = s.number("stiffness_factor", d.stiffness_factor, positive, "must be > 0");
  out.contact_stiffness =
      s.number("contact_stiffness", d.contact_stiffness, positive, "must be > 0 [kN/m^1.5]");
  out.damping_law = s.choice("damping_law", d.damping_law, integrators::damping_law_names());
  out.stick_slip_velocity =
      s.number("stick_slip_velocity", d.stick_slip_velocity, positive, "must be > 0 [m/s]");
  s.finish();
}

void read_output(Section s, OutputSettings& out) {
  s.only({"sample_dt"});
  out.sample_dt = s.number("sample_dt", 0.0, non_negative, "must be >= 0 [s] (0: every step)");
  s.finish();
}

// ---------------------------------------------------------------------------------------------
// Simple systems

std::unique_ptr<integrators::System> build_bouncing_ball(Section& m) {
  m.only({"kind", "mass", "height", "velocity", "restitution", "gravity"});
  BouncingBall::Parameters p;
  p.mass = m.number("mass", p.mass, positive, "must be > 0 [t]");
  p.height = m.number("height", p.height, non_negative, "must be >= 0 [m] (the initial gap)");
  p.velocity = m.number("velocity", p.velocity);
  p.restitution = m.number("restitution", p.restitution, unit_interval, "must be in [0, 1]");
  p.gravity = m.number("gravity", p.gravity, non_negative, "must be >= 0 [m/s^2]");
  m.finish();
  try {
    return std::make_unique<BouncingBall>(p);
  } catch (const std::invalid_argument& e) {
    m.rethrow(e);
  }
}

std::unique_ptr<integrators::System> build_impact_oscillator(Section& m) {
  m.only({"kind", "mass", "stiffness", "damping_ratio", "gap", "restitution", "initial_position", "initial_velocity", "force_amplitude", "force_frequency"});
  ImpactOscillator::Parameters p;
  p.mass = m.number("mass", p.mass, positive, "must be > 0 [t]");
  p.stiffness = m.number("stiffness", p.stiffness, non_negative, "must be >= 0 [kN/m]");
  p.damping_ratio = m.number("damping_ratio", p.damping_ratio, non_negative, "must be >= 0");
  p.gap = m.number("gap", p.gap);
  p.restitution = m.number("restitution", p.restitution, unit_interval, "must be in [0, 1]");
  p.initial_position = m.number("initial_position", p.initial_position);
  if (p.initial_position > p.gap) {
    m.fail(m.has("initial_position") ? "initial_position" : "gap",
           "initial penetration: initial_position (" + fmt(p.initial_position) +
               " m) must be <= gap (" + fmt(p.gap) + " m)");
  }
  p.initial_velocity = m.number("initial_velocity", p.initial_velocity);
  p.force_amplitude = m.number("force_amplitude", p.force_amplitude);
  p.force_frequency = m.number("force_frequency", p.force_frequency, non_negative, "must be >= 0 [Hz]");
  m.finish();
  try {
    return std::make_unique<ImpactOscillator>(p);
  } catch (const std::invalid_argument& e) {
    m.rethrow(e);
  }
}

std::unique_ptr<integrators::System> build_sliding_block(Section& m) {
  m.only({"kind", "mass", "friction", "gravity", "initial_velocity", "force", "force_amplitude", "force_frequency", "incline_deg"});
  SlidingBlock::Parameters p;
  p.mass = m.number("mass", p.mass, positive, "must be > 0 [t]");
  p.friction = m.number("friction", p.friction, non_negative, "must be >= 0");
  p.gravity = m.number("gravity", p.gravity, non_negative, "must be >= 0 [m/s^2]");
  p.initial_velocity = m.number("initial_velocity", p.initial_velocity);
  p.force = m.number("force", p.force);
  p.force_amplitude = m.number("force_amplitude", p.force_amplitude);
  p.force_frequency = m.number("force_frequency", p.force_frequency, non_negative, "must be >= 0 [Hz]");
  p.incline_deg = m.number("incline_deg", p.incline_deg,
                           [](double v) { return v > -90 && v < 90; }, "must be in (-90, 90) [deg]");
  m.finish();
  try {
    return std::make_unique<SlidingBlock>(p);
  } catch (const std::invalid_argument& e) {
    m.rethrow(e);
  }
}

std::unique_ptr<integrators::System> build_rigid_deck(Section& m) {
  m.only({"kind", "mass", "inertia", "length", "width", "skew_deg", "gap_right", "gap_left", "restitution", "friction", "initial_position", "initial_velocity"});
  RigidDeck::Parameters p;
  p.mass = m.number("mass", p.mass, positive, "must be > 0 [t]");
  p.inertia = m.number("inertia", p.inertia, positive, "must be > 0 [t m^2]");
  p.deck.length = m.number("length", p.deck.length, positive, "must be > 0 [m]");
  p.deck.width = m.number("width", p.deck.width, positive, "must be > 0 [m]");
  p.deck.skew_deg = m.number("skew_deg", p.deck.skew_deg, [](double v) { return std::abs(v) < 80; },
                        "must be in (-80, 80) [deg]");
  p.deck.gap_right = m.number("gap_right", p.deck.gap_right, non_negative, "must be >= 0 [m]");
  p.deck.gap_left = m.number("gap_left", p.deck.gap_left, non_negative, "must be >= 0 [m]");
  p.restitution = m.number("restitution", p.restitution, unit_interval, "must be in [0, 1]");
  p.friction = m.number("friction", p.friction, non_negative, "must be >= 0");
  p.initial_position = m.vec3("initial_position", p.initial_position);
  p.initial_velocity = m.vec3("initial_velocity", p.initial_velocity);
  m.finish();
  for (const char* k : {"mass", "inertia", "length", "width"}) {
    if (!m.has(k)) m.fail_table(std::string("missing key ") + k + " (required for rigid_deck)");
  }
  try {
    return std::make_unique<RigidDeck>(p);
  } catch (const std::invalid_argument& e) {
    m.rethrow(e);
  }
}

// ---------------------------------------------------------------------------------------------
// Bridge

// Finds a record file: absolute, next to the scene, in ../data/ beside it, or in ./data/.
fs::path find_record(Section& s, const std::string& key, const std::string& name,
                     const Context& c) {
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

Record read_record(Section& s, const std::string& key, const std::string& name, double unit,
                   const Context& c) {
  const fs::path path = find_record(s, key, name, c);
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  Record r;
  try {
    if (ext == ".at2") {
      r = read_at2(path, kStandardGravity);
    } else if (ext == ".csv") {
      r = read_csv(path, unit);
    } else {
      r = read_two_column(path, unit);
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
                      std::to_string(i + 1) + " (t = " + fmt(r.t[i]) + " s after " +
                      fmt(r.t[i - 1]) + " s)");
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
  MotionSet(std::optional<Record> r, GroundMotionOptions o) : record_(std::move(r)), options_(o) {}
  Bridge::Motion at_delay(double delay) {
    if (!record_) return nullptr;
    auto& m = cache_[delay];
    if (!m) {
      GroundMotionOptions o = options_;
      o.delay = delay;
      m = std::make_shared<const GroundMotion>(*record_, o);
    }
    return m;
  }

 private:
  std::optional<Record> record_;
  GroundMotionOptions options_;
  std::map<double, Bridge::Motion> cache_;
};

Bridge::Bent read_bent(Section& b) {
  b.only({"position", "height", "column_diameter", "columns", "elastic_modulus", "cracked_ratio",
          "yield_strain", "post_yield_ratio", "unloading_exponent", "stiffness_longitudinal",
          "yield_force_longitudinal", "stiffness_transverse", "yield_force_transverse", "delay"});
  Bridge::Bent bent;
  const auto pos = b.opt_number("position");
  if (!pos) b.fail_table("missing key position (bent position along the deck axis [m])");
  bent.position = *pos;
  BentDesign d;
  const auto height = b.opt_number("height", positive, "must be > 0 [m]");
  d.column_diameter = b.number("column_diameter", d.column_diameter, positive, "must be > 0 [m]");
  d.columns = b.integer("columns", d.columns, 1, 100);
  d.elastic_modulus = b.number("elastic_modulus", d.elastic_modulus, positive, "must be > 0 [kPa]");
  d.cracked_ratio = b.number("cracked_ratio", d.cracked_ratio,
                             [](double v) { return v > 0 && v <= 1; }, "must be in (0, 1]");
  d.yield_strain = b.number("yield_strain", d.yield_strain, positive, "must be > 0");
  d.post_yield_ratio = b.number("post_yield_ratio", d.post_yield_ratio,
                                [](double v) { return v >= 0 && v < 1; }, "must be in [0, 1)");
  d.unloading_exponent = b.number("unloading_exponent", d.unloading_exponent, unit_interval,
                                  "must be in [0, 1]");
  const char* dirs[2] = {"longitudinal", "transverse"};
  for (int k = 0; k < 2; ++k) {
    const std::string sk = std::string("stiffness_") + dirs[k];
    const std::string fk = std::string("yield_force_") + dirs[k];
    const auto stiff = b.opt_number(sk, positive, "must be > 0 [kN/m]");
    const auto fy = b.opt_number(fk, positive, "must be > 0 [kN]");
    if ((!stiff || !fy) && !height) {
      b.fail_table("missing key height (needed to derive " + (stiff ? fk : sk) +
                   "; give height, or both " + sk + " and " + fk + ")");
    }
    if (height) d.height = *height;
    const double kk = stiff ? *stiff : d.stiffness();
    const double ff = fy ? *fy : d.yield_force();
    (k == 0 ? bent.longitudinal : bent.transverse) =
        takeda::Parameters::bilinear(ff, ff / kk, d.post_yield_ratio, d.unloading_exponent);
  }
  return bent;
}

// The steps of building the bridge, in the order of the model (docs/bridge.md): the deck, its
// gaps, the damping, the bents, the seats, the excitation, and the support motions made from it.

void read_deck(Section& m, const Context& c, Bridge::Parameters& p) {
  const auto* t = m.table("deck");
  if (t == nullptr) return;
  Section s(c, *t, m.key_path("deck"));
  s.only({"mass", "inertia", "length", "width", "skew_deg", "initial_position", "initial_velocity"});
  p.mass = s.number("mass", p.mass, positive, "must be > 0 [t]");
  p.inertia = s.number("inertia", p.inertia, positive, "must be > 0 [t m^2]");
  p.deck.length = s.number("length", p.deck.length, positive, "must be > 0 [m]");
  p.deck.width = s.number("width", p.deck.width, positive, "must be > 0 [m]");
  p.deck.skew_deg = s.number("skew_deg", p.deck.skew_deg,
                             [](double v) { return std::abs(v) < 80; }, "must be in (-80, 80) [deg]");
  p.initial_position = s.vec3("initial_position", p.initial_position);
  p.initial_velocity = s.vec3("initial_velocity", p.initial_velocity);
  s.finish();
}

void read_gaps(Section& m, const Context& c, Bridge::Parameters& p) {
  const auto* t = m.table("gaps");
  if (t == nullptr) return;
  Section s(c, *t, m.key_path("gaps"));
  s.only({"left", "right"});
  p.deck.gap_left = s.number("left", p.deck.gap_left, non_negative, "must be >= 0 [m]");
  p.deck.gap_right = s.number("right", p.deck.gap_right, non_negative, "must be >= 0 [m]");
  s.finish();
}

void read_damping(Section& m, const Context& c, Bridge::Parameters& p) {
  const auto* t = m.table("damping");
  if (t == nullptr) return;
  Section s(c, *t, m.key_path("damping"));
  s.only({"ratio_i", "ratio_j", "mode_i", "mode_j"});
  const auto lt1 = [](double v) { return v >= 0 && v < 1; };
  p.damping_ratio_i = s.number("ratio_i", p.damping_ratio_i, lt1, "must be in [0, 1)");
  p.damping_ratio_j = s.number("ratio_j", p.damping_ratio_j, lt1, "must be in [0, 1)");
  p.damping_mode_i = s.integer("mode_i", p.damping_mode_i, 1, 3);
  p.damping_mode_j = s.integer("mode_j", p.damping_mode_j, 1, 3);
  if (p.damping_mode_i == p.damping_mode_j) s.fail("mode_j", "must differ from mode_i");
  s.finish();
}

// [[model.bents]]: the bents and the wave-passage delay of each [s].
std::vector<double> read_bents(Section& m, const Context& c, Bridge::Parameters& p) {
  std::vector<double> delays;
  const auto* bents = m.array_of_tables("bents");
  if (bents == nullptr || bents->size() < 2) {
    m.fail(bents == nullptr ? "kind" : "bents",
           "a bridge needs at least 2 [[model.bents]] (torsional stiffness)");
  }
  for (std::size_t j = 0; j < bents->size(); ++j) {
    Section s(c, *(*bents)[j].as_table(), m.key_path("bents") + "[" + std::to_string(j) + "]");
    p.bents.push_back(read_bent(s));
    if (std::abs(p.bents.back().position) > 0.5 * p.deck.length) {
      s.fail("position", "must lie on the deck, |position| <= length / 2 = " +
                             fmt(0.5 * p.deck.length) + " m (got " + fmt(p.bents.back().position) + ")");
    }
    delays.push_back(s.number("delay", 0.0, non_negative, "must be >= 0 [s]"));
    s.finish();
  }
  return delays;
}

// [model.seats]: the contact law and how the seats move.
struct SeatSettings {
  std::array<double, 2> delays{0.0, 0.0};           // wave-passage delay of each seat [s]
  bool transverse = false;                          // seats follow the transverse record too
  std::array<std::optional<Record>, 2> rotation;    // angular acceleration records [rad/s^2]
  double rotation_scale = 1.0;                      // factor on the rotation records
};

SeatSettings read_seats(Section& m, const Context& c, Bridge::Parameters& p) {
  SeatSettings out;
  const auto* t = m.table("seats");
  if (t == nullptr) return out;
  Section s(c, *t, m.key_path("seats"));
  s.only({"restitution", "friction", "transverse", "delay_left", "delay_right", "rotation_scale",
          "rotation_unit", "rotation_record_left", "rotation_record_right"});
  p.restitution = s.number("restitution", p.restitution, unit_interval, "must be in [0, 1]");
  p.friction = s.number("friction", p.friction, non_negative, "must be >= 0");
  out.transverse = s.boolean("transverse", false);
  out.delays[0] = s.number("delay_left", 0.0, non_negative, "must be >= 0 [s]");
  out.delays[1] = s.number("delay_right", 0.0, non_negative, "must be >= 0 [s]");
  out.rotation_scale = s.number("rotation_scale", 1.0);
  const double unit = s.number("rotation_unit", 1.0, positive, "must be > 0 [rad/s^2 per file unit]");
  const char* keys[2] = {"rotation_record_left", "rotation_record_right"};
  for (int a = 0; a < 2; ++a) {
    if (const auto name = s.opt_string(keys[a]); name && !name->empty()) {
      out.rotation[static_cast<std::size_t>(a)] = read_record(s, keys[a], *name, unit, c);
    }
  }
  s.finish();
  return out;
}

// [model.excitation]: the two records with their own factors, and the shared options.
struct ExcitationSettings {
  std::optional<Record> longitudinal, transverse;
  double longitudinal_factor = 1.0, transverse_factor = 1.0;  // amplitude factors
  GroundMotionOptions options;                                // time scale, baseline
};

// The factor that scales record r to target [g]; fails at key when the record is all zeros.
double factor_to(const Section& s, const std::string& key, const Record& r, double target) {
  const double pk = peak(r);
  if (!(pk > 0)) s.fail(key, "the record's peak acceleration is zero: cannot scale it");
  return target * kStandardGravity / pk;
}

ExcitationSettings read_excitation(Section& m, const Context& c) {
  ExcitationSettings out;
  const auto* t = m.table("excitation");
  if (t == nullptr) return out;
  Section s(c, *t, m.key_path("excitation"));
  s.only({"longitudinal_record", "transverse_record", "record_unit", "target_pga",
          "longitudinal_pga", "scale", "time_scale", "baseline_correction"});
  const double unit = s.number("record_unit", 1.0, positive, "must be > 0 [m/s^2 per file unit]");
  if (const auto n = s.opt_string("longitudinal_record"); n && !n->empty()) {
    out.longitudinal = read_record(s, "longitudinal_record", *n, unit, c);
  }
  if (const auto n = s.opt_string("transverse_record"); n && !n->empty()) {
    out.transverse = read_record(s, "transverse_record", *n, unit, c);
  }
  const double target = s.number("target_pga", 0.0, non_negative, "must be >= 0 [g] (0: as recorded)");
  const double target_x = s.number("longitudinal_pga", 0.0, non_negative,
                                   "must be >= 0 [g] (0: the factor of target_pga)");
  const double scale = s.number("scale", 1.0);
  out.options.time_scale = s.number("time_scale", 1.0, positive, "must be > 0");
  out.options.baseline_correction = s.boolean("baseline_correction", true);
  s.finish();
  // target_pga scales the transverse component (or the longitudinal one when it is alone);
  // without longitudinal_pga the other component takes the same factor. longitudinal_pga
  // gives the longitudinal component its own target (docs/bridge.md, "Target PGAs").
  const Record* ref = out.transverse ? &*out.transverse
                                     : (out.longitudinal ? &*out.longitudinal : nullptr);
  double common = 1.0;
  if (ref != nullptr && target > 0) common = factor_to(s, "target_pga", *ref, target);
  out.transverse_factor = scale * common;
  out.longitudinal_factor = scale * common;
  if (target_x > 0) {
    if (!out.longitudinal) s.fail("longitudinal_pga", "needs a longitudinal_record to scale");
    out.longitudinal_factor = scale * factor_to(s, "longitudinal_pga", *out.longitudinal, target_x);
  }
  out.options.target_pga = 0.0;
  return out;
}

// The support motions of every bent and seat, and the end of the longest bent motion [s].
Bridge::Excitation support_motions(const ExcitationSettings& e, const SeatSettings& seats,
                                   const std::vector<double>& bent_delays, double& end) {
  GroundMotionOptions ox = e.options, oy = e.options;
  ox.scale = e.longitudinal_factor;
  oy.scale = e.transverse_factor;
  MotionSet mx(e.longitudinal, ox), my(e.transverse, oy);
  GroundMotionOptions rot = e.options;
  rot.scale = seats.rotation_scale;
  Bridge::Excitation exc;
  for (double delay : bent_delays) {
    exc.bents.push_back({mx.at_delay(delay), my.at_delay(delay), nullptr});
  }
  for (std::size_t a = 0; a < 2; ++a) {
    exc.seats[a].longitudinal = mx.at_delay(seats.delays[a]);
    if (seats.transverse) exc.seats[a].transverse = my.at_delay(seats.delays[a]);
    if (seats.rotation[a]) {
      GroundMotionOptions o = rot;
      o.delay = seats.delays[a];
      exc.seats[a].rotation = std::make_shared<const GroundMotion>(*seats.rotation[a], o);
    }
  }
  end = 0.0;
  for (const auto& b : exc.bents) {
    for (const auto& mo : {b.longitudinal, b.transverse}) {
      if (mo) end = std::max(end, mo->end_time());
    }
  }
  return exc;
}

std::unique_ptr<integrators::System> build_bridge(Section& m, const Context& c,
                                                  SolverSettings& solver, bool end_time_given) {
  m.only({"kind", "deck", "gaps", "damping", "bents", "seats", "excitation"});
  Bridge::Parameters p = Bridge::Parameters::benchmark();
  p.bents.clear();
  read_deck(m, c, p);
  read_gaps(m, c, p);
  read_damping(m, c, p);
  const std::vector<double> bent_delays = read_bents(m, c, p);
  const SeatSettings seats = read_seats(m, c, p);
  const ExcitationSettings excitation = read_excitation(m, c);
  double end = 0.0;
  Bridge::Excitation exc = support_motions(excitation, seats, bent_delays, end);
  if (!end_time_given && end > 0) solver.end_time = end;

  try {
    return std::make_unique<Bridge>(p, std::move(exc));
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    if (msg.rfind("initial_position", 0) == 0) {
      const auto* deck = m.table("deck");
      if (deck != nullptr) {
        Section s(c, *deck, m.key_path("deck"));
        s.rethrow(e);
      }
    }
    m.rethrow(e);
  }
}

}  // namespace

void SolverSettings::validate() const {
  auto bad = [](const std::string& f, const std::string& w) {
    throw std::invalid_argument("solver." + f + ": " + w);
  };
  if (method != "moreau" && method != "event_driven" && method != "compliance")
    bad("method", "must be \"moreau\", \"event_driven\" or \"compliance\"");
  if (!(std::isfinite(end_time) && end_time > 0)) bad("end_time", "must be > 0 [s]");
  if (!(std::isfinite(step) && step > 0 && step <= end_time)) bad("step", "must be in (0, end_time] [s]");
  if (!(theta >= 0.5 && theta <= 1.0)) bad("theta", "must be in [0.5, 1]");
  if (!(tolerance > 0 && tolerance < 1)) bad("tolerance", "must be in (0, 1)");
  if (!lcp::parse_solver(lcp_solver)) bad("lcp_solver", "must be lemke, pgs, nfb or enum");
  if (!(std::isfinite(stiffness_factor) && stiffness_factor > 0)) bad("stiffness_factor", "must be > 0");
  if (!(std::isfinite(contact_stiffness) && contact_stiffness > 0))
    bad("contact_stiffness", "must be > 0 [kN/m^1.5]");
  const auto& laws = integrators::damping_law_names();
  if (std::find(laws.begin(), laws.end(), damping_law) == laws.end())
    bad("damping_law", "unknown damping law");
  if (!(std::isfinite(stick_slip_velocity) && stick_slip_velocity > 0))
    bad("stick_slip_velocity", "must be > 0 [m/s]");
}

void OutputSettings::validate() const {
  if (!(std::isfinite(sample_dt) && sample_dt >= 0))
    throw std::invalid_argument("output.sample_dt: must be >= 0 [s]");
}

integrators::RunConfig make_run_config(const SolverSettings& s) {
  s.validate();
  const lcp::Solver solver = *lcp::parse_solver(s.lcp_solver);
  if (s.method == "moreau") {
    integrators::MoreauJeanOptions o;
    o.end_time = s.end_time;
    o.step = s.step;
    o.theta = s.theta;
    o.solver = solver;
    return o;
  }
  if (s.method == "event_driven") {
    integrators::EventDrivenOptions o;
    o.end_time = s.end_time;
    o.tolerance = s.tolerance;
    o.solver = solver;
    return o;
  }
  integrators::ComplianceOptions o;
  o.end_time = s.end_time;
  o.tolerance = s.tolerance;
  o.stiffness = s.contact_stiffness;
  o.stiffness_factor = s.stiffness_factor;
  o.stick_slip_velocity = s.stick_slip_velocity;
  o.law = integrators::parse_damping_law(s.damping_law);
  return o;
}

const std::vector<std::string>& scene_kinds() {
  static const std::vector<std::string> k{"bridge", "rigid_deck", "bouncing_ball",
                                          "impact_oscillator", "sliding_block"};
  return k;
}

Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  Context ctx;
  ctx.file = file.string();
  ctx.dir = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    throw std::invalid_argument(ctx.file + ": cannot open scene file (not found)");
  }
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << ctx.file << ':' << e.source().begin.line << ':' << e.source().begin.column
      << ": TOML syntax error: " << e.description();
    throw std::invalid_argument(s.str());
  }
  for (const auto& o : overrides) apply_override(root, o, ctx);

  Scene scene;
  scene.path = file;
  scene.name = file.stem().string();
  Section top(ctx, root, "");
  const toml::table* model = top.table("model");
  if (model == nullptr) top.fail_table("missing table [model]");
  const toml::table* solver = top.table("solver");
  const toml::table* output = top.table("output");
  top.opt_string("description");
  top.finish({"description", "model", "solver", "output"});

  Section m(ctx, *model, "model");
  const auto kind = m.opt_string("kind");
  if (!kind) m.fail_table("missing key kind (one of bridge, rigid_deck, bouncing_ball, impact_oscillator, sliding_block)");
  scene.kind = m.choice("kind", *kind, scene_kinds());

  bool end_time_given = false;
  if (solver != nullptr) {
    end_time_given = solver->get("end_time") != nullptr;
    read_solver(Section(ctx, *solver, "solver"), scene.solver);
  }
  if (output != nullptr) read_output(Section(ctx, *output, "output"), scene.output);

  if (scene.kind == "bouncing_ball") {
    scene.system = build_bouncing_ball(m);
  } else if (scene.kind == "impact_oscillator") {
    scene.system = build_impact_oscillator(m);
  } else if (scene.kind == "sliding_block") {
    scene.system = build_sliding_block(m);
  } else if (scene.kind == "rigid_deck") {
    scene.system = build_rigid_deck(m);
  } else {
    scene.system = build_bridge(m, ctx, scene.solver, end_time_given);
    if (scene.solver.step > scene.solver.end_time) {
      throw std::invalid_argument(ctx.file + ": solver.step: must be <= end_time (" +
                                  fmt(scene.solver.end_time) + " s)");
    }
  }
  scene.solver.validate();
  scene.output.validate();
  scene.run = make_run_config(scene.solver);
  // Every record of a scene shares the excitation's time_scale (validated above).
  scene.record_step = ctx.record_step *
                      root.at_path("model.excitation.time_scale").value<double>().value_or(1.0);
  return scene;
}

}  // namespace nsb::models
