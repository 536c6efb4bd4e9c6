// Design files: expansion of every mode, the value generators, and the errors reported before
// any run. Expected values come from the definitions (full factorial order, the closed forms
// of linspace and logspace, the Latin-hypercube stratification property), not from the code.
#include "sweep/design.hpp"

#include "io/csv.hpp"

#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>

namespace fs = std::filesystem;
using nsb::sweep::Design;
using nsb::sweep::load_design;
using nsb::sweep::Mode;
using nsb::sweep::OutputSpec;
using nsb::sweep::validate_design;

namespace {

const std::string kScenes = NSB_SCENES_DIR;

// Writes a design into a fresh folder; the base scene is given by absolute path.
fs::path write_design(const std::string& name, const std::string& body) {
  const fs::path dir =
      fs::temp_directory_path() / ("nsb_design_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / (name + ".toml");
  std::ofstream(file) << body;
  return file;
}

std::string scene_line(const std::string& scene = "bouncing-ball") {
  return "scene = \"" + kScenes + "/" + scene + ".toml\"\n";
}

// Overrides as their texts "key=value" (scene::to_string: the value as toml++ writes it, so a
// double keeps its ".0" and a string is a literal string in single quotes).
std::vector<std::string> texts(const std::vector<nsb::scene::Override>& overrides) {
  std::vector<std::string> out;
  for (const auto& o : overrides) out.push_back(nsb::scene::to_string(o));
  return out;
}

// The message of the std::invalid_argument that f throws, or "" when it throws none.
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST_CASE("grid: full factorial, first factor slowest, ids zero-padded") {
  const Design d = load_design(write_design("grid", scene_line() + R"(
set = ["solver.end_time=1"]
[[factor]]
key = "model.restitution"
values = [0.5, 0.9, 1]
[[factor]]
key = "solver.method"
values = ["moreau", "event_driven"]
)"));
  REQUIRE(d.runs.size() == 6);  // 3 x 2
  CHECK(d.runs[0].id == "0000");
  CHECK(d.runs[5].id == "0005");
  const std::vector<std::vector<std::string>> labels = {{"0.5", "moreau"}, {"0.5", "event_driven"},
                                                        {"0.9", "moreau"}, {"0.9", "event_driven"},
                                                        {"1", "moreau"},   {"1", "event_driven"}};
  for (std::size_t i = 0; i < 6; ++i) CHECK(d.runs[i].labels == labels[i]);
  // The fixed overrides first, then one per factor, each value of the type the design gives it
  // ("1" in `set` is an integer, a TOML float stays a double, a string a string).
  CHECK(texts(d.runs[1].overrides) == std::vector<std::string>{"solver.end_time=1",
                                                               "model.restitution=0.5",
                                                               "solver.method='event_driven'"});
  CHECK(std::get<std::int64_t>(d.runs[5].overrides[1].value) == 1);  // `1`: a TOML integer
  CHECK_NOTHROW(validate_design(d));
}

TEST_CASE("a factor's value reaches the scene as the design's value, without a text between") {
  // 0.1 + 0.2 = 0.30000000000000004 (the double nearest 0.3 is 0.29999999999999998890): its
  // shortest text has 17 digits; the override holds the double itself, and its label is that
  // shortest text, which reads back to the same double.
  const Design d = load_design(write_design("typed", scene_line() + R"(
[[factor]]
key = "model.restitution"
values = [0.30000000000000004, 1, true, "x"]
)"));
  REQUIRE(d.runs.size() == 4);
  CHECK(std::get<double>(d.runs[0].overrides[0].value) == 0.1 + 0.2);
  CHECK(d.runs[0].labels[0] == "0.30000000000000004");
  CHECK(std::get<std::int64_t>(d.runs[1].overrides[0].value) == 1);
  CHECK(std::get<bool>(d.runs[2].overrides[0].value));
  CHECK(std::get<std::string>(d.runs[3].overrides[0].value) == "x");
  // The base scene is read once, with no override: its table is the file's.
  CHECK(d.base.overridden.empty());
  CHECK(d.coordinates == std::vector<std::string>{"y"});  // the bouncing ball: one coordinate
}

TEST_CASE("the inputs: the base scene and every record file a run reads, by content") {
  const fs::path file = write_design("inputs", scene_line("bridge-exc5") + R"(
[[factor]]
key = "record"
records = [ { name = "one", transverse = "in-a.AT2" } ]
)");
  const fs::path record = file.parent_path() / "in-a.AT2";
  fs::copy_file(kScenes + "/../data/ground-motions/RSN6_IMPVALL.I_I-ELC180.AT2", record,
                fs::copy_options::overwrite_existing);
  const Design a = load_design(file);
  // bridge-exc5's own records are its transverse (replaced by the factor) and longitudinal one.
  REQUIRE(a.inputs.size() == 3);
  CHECK(a.inputs[0].path == fs::path(kScenes + "/bridge-exc5.toml").lexically_normal());
  const auto named = [&](const Design& d) {
    return std::find_if(d.inputs.begin(), d.inputs.end(),
                        [&](const auto& i) { return i.path == record.lexically_normal(); });
  };
  REQUIRE(named(a) != a.inputs.end());
  CHECK(named(a)->name == "in-a.AT2");
  // FNV-1a of the empty string is its offset basis; of "a" the published test vector.
  CHECK(nsb::sweep::content_hash("") == "cbf29ce484222325");
  CHECK(nsb::sweep::content_hash("a") == "af63dc4c8601ec8c");
  std::ofstream(record, std::ios::app) << "\n";  // one byte more: another content
  const Design b = load_design(file);
  CHECK(named(b)->hash != named(a)->hash);
  CHECK(b.hash != a.hash);
}

TEST_CASE("linspace and logspace: closed forms, both ends exact") {
  const Design d = load_design(write_design("spaced", scene_line() + R"(
[[factor]]
key = "model.height"
linspace = [0.5, 1.5, 5]
[[factor]]
key = "model.gravity"
logspace = [0.01, 100, 5]
)"));
  REQUIRE(d.factors.size() == 2);
  const auto& lin = d.factors[0].levels;
  const auto& log = d.factors[1].levels;
  REQUIRE(lin.size() == 5);
  REQUIRE(log.size() == 5);
  // a + (b - a) i / (n - 1): 0.5, 0.75, 1, 1.25, 1.5 are all exact in binary.
  const char* lin_expected[] = {"0.5", "0.75", "1", "1.25", "1.5"};
  for (int i = 0; i < 5; ++i) CHECK(lin[static_cast<std::size_t>(i)].label == lin_expected[i]);
  // Geometric: 10^(-2 + i); the inner points within a few ulp of the powers of ten.
  CHECK(log.front().label == "0.01");
  CHECK(log.back().label == "100");
  for (int i = 1; i < 4; ++i) {
    const double v = std::stod(log[static_cast<std::size_t>(i)].label);
    CHECK(v == doctest::Approx(std::pow(10.0, i - 2)).epsilon(1e-14));
  }
  CHECK(d.runs.size() == 25);
}

TEST_CASE("latin: every stratum of every factor holds exactly one run; the seed decides") {
  const auto text = [](int seed) {
    return scene_line() + "mode = \"latin\"\nsamples = 8\nseed = " + std::to_string(seed) + R"(
[[factor]]
key = "model.height"
range = [1.0, 3.0]
[[factor]]
key = "model.restitution"
values = [0.1, 0.2, 0.3, 0.4]
)";
  };
  const Design a = load_design(write_design("latin_a", text(7)));
  const Design b = load_design(write_design("latin_b", text(7)));
  const Design c = load_design(write_design("latin_c", text(8)));
  REQUIRE(a.runs.size() == 8);
  std::set<int> strata;
  std::vector<int> per_level(4, 0);
  for (const auto& r : a.runs) {
    const double h = std::stod(r.labels[0]);
    REQUIRE(h >= 1.0);
    REQUIRE(h < 3.0);
    strata.insert(static_cast<int>((h - 1.0) / 2.0 * 8.0));  // stratum width 2/8
    ++per_level[static_cast<std::size_t>(std::lround(std::stod(r.labels[1]) * 10.0) - 1)];
  }
  CHECK(strata.size() == 8);  // one run in each of the 8 strata
  // 8 strata over 4 levels: each level covers 2 strata.
  CHECK(per_level == std::vector<int>{2, 2, 2, 2});
  CHECK(a.hash == b.hash);
  for (std::size_t i = 0; i < 8; ++i) CHECK(a.runs[i].labels == b.runs[i].labels);
  CHECK(a.hash != c.hash);
}

TEST_CASE("latin_hypercube: the draws of latin mode, one per stratum of each factor") {
  const auto d = nsb::sweep::latin_hypercube(8, 3, 7);
  REQUIRE(d.size() == 3);
  for (const auto& f : d) {
    REQUIRE(f.size() == 8);
    std::set<int> strata;
    for (double u : f) {
      REQUIRE(u >= 0.0);
      REQUIRE(u < 1.0);
      strata.insert(static_cast<int>(u * 8.0));
    }
    CHECK(strata.size() == 8);
  }
  // The first factor of the latin design above (seed 7, range [1, 3]) is this draw mapped
  // linearly: 1 + 2 u.
  const Design a = load_design(write_design("latin_draws", scene_line() + R"(
mode = "latin"
samples = 8
seed = 7
[[factor]]
key = "model.height"
range = [1.0, 3.0]
)"));
  const auto one = nsb::sweep::latin_hypercube(8, 1, 7);
  for (std::size_t i = 0; i < 8; ++i) {
    const double h = std::stod(a.runs[i].labels[0]);
    CHECK(h == doctest::Approx(1.0 + 2.0 * one[0][i]).epsilon(1e-15));
  }
  CHECK(nsb::sweep::latin_hypercube(0, 2, 1)[0].empty());
}

TEST_CASE("oat: the base run, then each level of each factor alone") {
  const Design d = load_design(write_design("oat", scene_line() + R"(
mode = "oat"
[[factor]]
key = "model.restitution"
values = [0.5, 0.7]
[[factor]]
key = "model.height"
values = [2.0, 3.0, 4.0]
)"));
  REQUIRE(d.runs.size() == 6);  // 1 + 2 + 3
  CHECK(d.runs[0].labels == std::vector<std::string>{"", ""});
  CHECK(d.runs[0].overrides.empty());
  CHECK(d.runs[2].labels == std::vector<std::string>{"0.7", ""});
  CHECK(d.runs[5].labels == std::vector<std::string>{"", "4"});
  CHECK(texts(d.runs[5].overrides) == std::vector<std::string>{"model.height=4.0"});
}

TEST_CASE("records: one level per record, each component mapped to its scene key") {
  const fs::path file = write_design("records", scene_line("bridge-exc5") + R"(
[[factor]]
key = "record"
records = [
  { name = "sylmar", transverse = "a.AT2", longitudinal = "b.AT2" },
  { transverse = "elCentro.AT2" },
]
)");
  std::ofstream(file.parent_path() / "a.AT2") << "";
  const Design d = load_design(file);
  REQUIRE(d.factors[0].levels.size() == 2);
  const auto& sylmar = d.factors[0].levels[0];
  CHECK(sylmar.label == "sylmar");
  // a.AT2 exists beside the design: resolved there; b.AT2 does not: left to the scene's lookup.
  CHECK(texts(sylmar.overrides) ==
        std::vector<std::string>{"model.excitation.transverse_record='" +
                                     (file.parent_path() / "a.AT2").string() + "'",
                                 "model.excitation.longitudinal_record='b.AT2'"});
  CHECK(d.factors[0].levels[1].label == "elCentro");  // the file's stem by default
}

TEST_CASE("list: the rows of a CSV, with named levels selected by name") {
  const fs::path file = write_design("list", scene_line() + R"(
mode = "list"
runs = "list-runs.csv"
[[factor]]
key = "drop"
levels = [ { name = "low", set = ["model.height=0.5"] }, { name = "high", set = ["model.height=2"] } ]
)");
  std::ofstream(file.parent_path() / "list-runs.csv")
      << "# a comment\ndrop,model.restitution\nlow,0.5\nhigh,\"0.75\"\nhigh,\n";
  const Design d = load_design(file);
  REQUIRE(d.runs.size() == 3);
  CHECK(texts(d.runs[0].overrides) ==
        std::vector<std::string>{"model.height=0.5", "model.restitution=0.5"});
  CHECK(texts(d.runs[1].overrides) ==
        std::vector<std::string>{"model.height=2", "model.restitution=0.75"});
  CHECK(texts(d.runs[2].overrides) == std::vector<std::string>{"model.height=2"});  // empty: base
  CHECK_NOTHROW(validate_design(d));
}

TEST_CASE("the hash changes with any value, not with a rewrite of the same design") {
  const auto body = [](const std::string& v) {
    return scene_line() + "[[factor]]\nkey = \"model.restitution\"\nvalues = [" + v + "]\n";
  };
  const Design a = load_design(write_design("h1", body("0.5, 0.9")));
  const Design b = load_design(write_design("h2", "# same runs\n" + body("0.50, 0.90")));
  const Design c = load_design(write_design("h3", body("0.5, 0.8")));
  CHECK(a.hash == b.hash);
  CHECK(a.hash != c.hash);
  CHECK(load_design(write_design("h4", body("0.5, 0.9")), {"solver.end_time=2"}).hash != a.hash);
}

TEST_CASE("design errors name the file, the line and the key") {
  struct Case {
    std::string body;
    std::string expected;  // a part of the message
  };
  const std::vector<Case> cases = {
      {"[[factor]]\nkey = \"model.height\"\nvalues = []\n",
       ":4:10: factor[0].values: must not be empty"},
      {"colour = 1\n[[factor]]\nkey = \"a\"\nvalues = [1]\n", ":2:10: colour: unknown key"},
      {"[[factor]]\nkey = \"model.height\"\nvalues = [1]\n[[factor]]\nkey = "
       "\"model.height\"\nvalues = [2]\n",
       "factor[1].key: \"model.height\" appears twice"},
      {"[[factor]]\nkey = \"model.height\"\nvalues = [1, 1.0]\n", "level \"1\" appears twice"},
      {"[[factor]]\nkey = \"model.height\"\nrange = [1, 2]\n",
       "factor[0].range: only for mode = \"latin\""},
      {"mode = \"spiral\"\n[[factor]]\nkey = \"a\"\nvalues = [1]\n", ":2:8: mode: must be"},
      {"[[factor]]\nkey = \"model.height\"\nlinspace = [1, 2]\n",
       "linspace: must be [first, last, count]"},
      {"[[factor]]\nkey = \"model.height\"\nvalues = [1]\nlinspace = [1, 2, 3]\n",
       "give exactly one of"},
      {"mode = \"list\"\nruns = \"missing.csv\"\n", "runs: cannot read"},
      {"", "factor: grid: at least one [[factor]]"},
  };
  for (const auto& c : cases) {
    const fs::path file = write_design("bad", scene_line() + c.body);
    const std::string message = error_of([&] { (void)load_design(file); });
    INFO(c.body);
    CHECK(message.find(file.string()) == 0);
    CHECK(message.find(c.expected) != std::string::npos);
  }
}

TEST_CASE("validation: an unknown key or a value the scene rejects, with the factor's line") {
  const fs::path unknown = write_design("unknown", scene_line() + R"(
[[factor]]
key = "model.restitution"
values = [0.5]

[[factor]]
key = "model.colour"
values = [1]
)");
  const Design d = load_design(unknown);                        // the design is well formed ...
  const std::string m = error_of([&] { validate_design(d); });  // ... the scene refuses the key
  CHECK(m.find(unknown.string() + ":7: factor model.colour = 1: ") == 0);
  CHECK(m.find("model.colour") != std::string::npos);

  const fs::path bad_value = write_design("bad_value", scene_line() + R"(
[[factor]]
key = "model.restitution"
values = [0.5, 1.5]
)");
  const std::string v = error_of([&] { validate_design(load_design(bad_value)); });
  CHECK(v.find(":3: factor model.restitution = 1.5: ") != std::string::npos);
  CHECK(v.find("[0, 1]") != std::string::npos);  // the scene's allowed range

  const fs::path bad_set = write_design("bad_set", scene_line() + R"(
set = ["solver.end_time=-1"]
[[factor]]
key = "model.restitution"
values = [0.5]
)");
  CHECK(error_of([&] { validate_design(load_design(bad_set)); }).find(": scene: ") !=
        std::string::npos);
}

TEST_CASE("labels and results.csv: io::csv_number, the shortest text that reads back to the same double") {
  CHECK(nsb::io::csv_number(0.1) == "0.1");
  CHECK(nsb::io::csv_number(1e-5) == "1e-05");
  CHECK(nsb::io::csv_number(0.1 + 0.2) == "0.30000000000000004");
  CHECK(nsb::io::csv_number(std::nan("")).empty());
  for (const double v : {1.0 / 3.0, 2.0 / 3.0 * 1e-300, 123456.789e10}) {
    CHECK(std::stod(nsb::io::csv_number(v)) == v);
  }
}

TEST_CASE("every shipped design in scenes/sweeps/ is valid") {
  int designs = 0;
  for (const auto& entry : fs::directory_iterator(kScenes + "/sweeps")) {
    if (entry.path().extension() != ".toml") continue;
    INFO(entry.path().string());
    Design d;
    CHECK_NOTHROW(d = load_design(entry.path()));
    CHECK_NOTHROW(validate_design(d));
    CHECK(!d.runs.empty());
    ++designs;
  }
  CHECK(designs >= 3);
  // Fig. 6: 6 distinct excitations x with/without pounding x 3 friction coefficients.
  CHECK(load_design(kScenes + "/sweeps/fig6.toml").runs.size() == 36);
}

TEST_CASE("[output] hdf5_history: all, none or columns, and not part of the design's hash") {
  const std::string factors = R"(
[[factor]]
key = "model.restitution"
values = [0.5, 0.9]
)";
  const Design plain = load_design(write_design("output_plain", scene_line() + factors));
  CHECK(plain.output.history == OutputSpec::History::kAll);  // the default
  const Design none = load_design(
      write_design("output_none", scene_line() + factors + "[output]\nhdf5_history = \"none\"\n"));
  CHECK(none.output.history == OutputSpec::History::kNone);
  const Design some = load_design(write_design(
      "output_some", scene_line() + factors + "[output]\nhdf5_history = [\"y\", \"vy\"]\n"));
  CHECK(some.output.history == OutputSpec::History::kColumns);
  CHECK(some.output.columns == std::vector<std::string>{"y", "vy"});
  CHECK(some.output.line == 7);  // scene, then the factor's four lines, then [output]
  // The section changes no run: the same hash, so a changed selection reruns nothing.
  CHECK(some.hash == plain.hash);
  CHECK(none.hash == plain.hash);
  // Refused at its line and column: a value of another type, a name twice, an unknown key.
  const auto error = [&](const std::string& name, const std::string& section) {
    const fs::path file = write_design(name, scene_line() + factors + section);
    return error_of([&] { (void)load_design(file); });
  };
  CHECK(error("output_bad", "[output]\nhdf5_history = 3\n").find(
            ":7:16: output.hdf5_history: must be \"all\", \"none\" or an array") !=
        std::string::npos);
  CHECK(error("output_twice", "[output]\nhdf5_history = [\"y\", \"y\"]\n")
            .find(":7:22: output.hdf5_history: \"y\" appears twice") != std::string::npos);
  CHECK(error("output_key", "[output]\nhdf5 = \"all\"\n").find("output.hdf5: unknown key") !=
        std::string::npos);
}
