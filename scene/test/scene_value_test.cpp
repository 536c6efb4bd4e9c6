// A scene as a value (scene/scene.hpp): a scene built from a table in code runs exactly as the
// same scene read from a file; typed overrides give the same scene as their text form; a table
// without source positions names the key of a bad value; to_toml reads back to the same scene.
#include "scene/scene.hpp"
#include "scene/test/scene_files.hpp"

#include "integrators/recorder.hpp"
#include "integrators/run.hpp"

#include <doctest/doctest.h>
#include <toml++/toml.h>

#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
namespace ns = nsb::scene;
namespace ni = nsb::integrators;

namespace {

using ns::test_files::write;

const fs::path kScenes = NSB_SCENES_DIR;
const fs::path kData = NSB_DATA_DIR;
const std::string kRecord = "ground-motions/RSN988_NORTHR_CCN360.AT2";

// The history of a run of the scene, every sample (sample_dt = 0 records every step).
ni::Recorder run(ns::Scene& scene) {
  ni::Recorder rec(*scene.system, 0.0);
  const ni::RunResult r = ni::integrate(*scene.system, scene.run, rec);
  CHECK(r.status == ni::RunStatus::kCompleted);
  return rec;
}

// The scene of a file with typed overrides.
ns::Scene load_typed(const fs::path& file, const std::vector<ns::Override>& overrides) {
  ns::SceneTable t = ns::read_scene_table(file);
  ns::apply_overrides(t, overrides);
  return ns::build_scene(t);
}

// The number of history entries that differ in their bits (0 when the runs are identical).
std::size_t differing(const ni::Recorder& a, const ni::Recorder& b) {
  REQUIRE(a.columns() == b.columns());
  REQUIRE(a.rows() == b.rows());
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.rows(); ++i) {
    for (std::size_t j = 0; j < a.columns().size(); ++j) {
      const double x = a.at(i, j), y = b.at(i, j);
      if (std::memcmp(&x, &y, sizeof x) != 0) ++n;
    }
  }
  return n;
}

// A three-bent bridge with one record, 0.3 s of it, as TOML text with the record path given.
std::string bridge_text(const std::string& record) {
  return R"([model]
kind = "bridge"
[[model.bents]]
position = -8.34
height = 1.83
[[model.bents]]
position = 0.0
height = 2.44
[[model.bents]]
position = 8.34
height = 1.52
[model.excitation]
time_scale = 0.5
transverse_record = ")" + record + R"("
target_pga = 0.5
[solver]
end_time = 0.3
step = 1e-4
)";
}

// The same bridge as a table built in code.
toml::table bridge_table(const std::string& record) {
  toml::array bents;
  bents.push_back(toml::table{{"position", -8.34}, {"height", 1.83}});
  bents.push_back(toml::table{{"position", 0.0}, {"height", 2.44}});
  bents.push_back(toml::table{{"position", 8.34}, {"height", 1.52}});
  return toml::table{
      {"model", toml::table{{"kind", "bridge"},
                            {"bents", bents},
                            {"excitation", toml::table{{"time_scale", 0.5},
                                                       {"transverse_record", record},
                                                       {"target_pga", 0.5}}}}},
      {"solver", toml::table{{"end_time", 0.3}, {"step", 1e-4}}},
  };
}

// The message of building the table (empty when it builds).
std::string error_of(const ns::SceneTable& t) {
  try {
    (void)ns::build_scene(t);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST_CASE("a bridge built from a table runs bit for bit as the same bridge read from a file") {
  // The file names the record by its absolute path; the table by a path relative to its
  // origin's folder, which is where records are looked up from.
  ns::Scene from_file =
      ns::load_scene(write("table_bridge.toml", bridge_text((kData / kRecord).string())));
  ns::SceneTable t{bridge_table(kRecord), {"<table>", kData}, {}};
  ns::Scene from_table = ns::build_scene(t);
  CHECK(from_table.name == "<table>");
  CHECK(from_table.kind == "bridge");
  CHECK(from_table.record_step == from_file.record_step);
  const ni::Recorder a = run(from_file);
  const ni::Recorder b = run(from_table);
  // 0.3 s at 1e-4 s: 3000 steps and the initial row.
  CHECK(a.rows() == 3001);
  CHECK(differing(a, b) == 0);
}

TEST_CASE("parse_override: a TOML value, else the text as a string") {
  const ns::Override step = ns::parse_override("solver.step=2e-4");
  CHECK(step.key == "solver.step");
  CHECK(std::get<double>(step.value) == 2e-4);
  CHECK(std::get<std::int64_t>(ns::parse_override("model.damping.mode_j = 3").value) == 3);
  CHECK(std::get<bool>(ns::parse_override("model.seats.transverse=true").value));
  CHECK(std::get<std::string>(ns::parse_override("solver.method=event_driven").value) ==
        "event_driven");
  CHECK(std::get<std::string>(ns::parse_override("model.excitation.scale_to=\"sa\"").value) ==
        "sa");
  CHECK(std::get<std::vector<double>>(
            ns::parse_override("model.decks.0.initial_position=[0.01, 0, -2]").value) ==
        std::vector<double>{0.01, 0.0, -2.0});
  CHECK_THROWS_AS(ns::parse_override("solver.step"), std::invalid_argument);
  CHECK_THROWS_AS(ns::parse_override("step=1"), std::invalid_argument);
  CHECK_THROWS_AS(ns::parse_override("model.x={a = 1}"), std::invalid_argument);
  // The text form reads back to the same override.
  for (const char* text : {"solver.step=2e-4", "model.damping.mode_j=3", "solver.method=lemke",
                           "model.seats.transverse=false", "model.decks.0.initial_position=[1, 2.5, 3]"}) {
    const ns::Override o = ns::parse_override(text);
    const ns::Override back = ns::parse_override(ns::to_string(o));
    CHECK(back.key == o.key);
    CHECK(back.value == o.value);
  }
}

TEST_CASE("typed overrides give the scene of their text form, bit for bit") {
  const fs::path file = kScenes / "bridge-exc7.toml";
  const std::vector<std::string> text = {"solver.end_time=0.2", "solver.step=2e-4",
                                         "model.gaps.left=0.05", "model.bents.0.height=2.0",
                                         "model.damping.mode_j=2", "solver.method=moreau",
                                         "model.seats.transverse=true"};
  const std::vector<ns::Override> typed = {
      {"solver.end_time", 0.2},          {"solver.step", 2e-4},
      {"model.gaps.left", 0.05},         {"model.bents.0.height", 2.0},
      {"model.damping.mode_j", std::int64_t{2}}, {"solver.method", std::string("moreau")},
      {"model.seats.transverse", true}};
  ns::Scene a = ns::load_scene(file, text);
  ns::Scene b = load_typed(file, typed);
  CHECK(ns::to_toml(a.table) == ns::to_toml(b.table));
  CHECK(a.table.overridden == b.table.overridden);
  CHECK(differing(run(a), run(b)) == 0);
  // The overridden gap reached the scene: the text shows it.
  CHECK(ns::to_toml(a.table).find("left = 0.05") != std::string::npos);

  // A bad typed value is reported as the text form's is.
  const auto error = [&](const auto& overrides) {
    try {
      ns::SceneTable t = ns::read_scene_table(file);
      ns::apply_overrides(t, overrides);
      (void)ns::build_scene(t);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string from_text = error(std::vector<std::string>{"solver.step=-1"});
  CHECK(from_text.find("solver.step (override): ") != std::string::npos);
  CHECK(error(std::vector<ns::Override>{{"solver.step", -1.0}}) == from_text);
  CHECK(error(std::vector<ns::Override>{{"model.bents.7.height", 1.0}}) ==
        error(std::vector<std::string>{"model.bents.7.height=1.0"}));
}

TEST_CASE("a bad value in a table names its key, without a line and column") {
  const std::string text = R"([model]
kind = "bouncing_ball"
mass = -1.0
height = 1.0
)";
  const std::string from_file = ns::test_files::error_of("bad_mass.toml", text);
  const std::string from_table =
      error_of({toml::parse(text), {"<table>", "."}, {}});  // a parsed text keeps its positions
  toml::table t{{"model", toml::table{{"kind", "bouncing_ball"}, {"mass", -1.0},
                                      {"height", 1.0}}}};
  const std::string no_positions = error_of({t, {"<table>", "."}, {}});
  // The file's message "<file>:3:8: model.mass: <why>"; the table's "<table>: model.mass: <why>".
  const auto why = from_file.substr(from_file.find("model.mass: "));
  CHECK(from_file.find("bad_mass.toml:3:8: model.mass: ") != std::string::npos);
  CHECK(from_table.find("<table>:3:8: model.mass: ") == 0);
  CHECK(no_positions == "<table>: " + why);

  t["model"].as_table()->insert("masss", 2.0);
  CHECK(error_of({t, {"<table>", "."}, {}}).find("<table>: model.masss: unknown key") == 0);
}

TEST_CASE("to_toml reads back to the same scene") {
  for (const auto& entry : fs::directory_iterator(kScenes)) {
    if (entry.path().extension() != ".toml") continue;
    CAPTURE(entry.path());
    const ns::SceneTable t = ns::read_scene_table(entry.path());
    const std::string text = ns::to_toml(t);
    const ns::SceneTable back{toml::parse(text), t.origin, {}};
    CHECK(back.table == t.table);
    CHECK(ns::to_toml(back) == text);
  }
  // A short run of an overridden bridge from its text equals the run of the scene itself.
  const fs::path file = kScenes / "bridge-exc5.toml";
  ns::Scene a = ns::load_scene(file, std::vector<std::string>{"solver.end_time=0.2",
                                                              "model.gaps.right=0.02"});
  ns::Scene b = ns::build_scene({toml::parse(ns::to_toml(a.table)), a.table.origin, {}});
  CHECK(differing(run(a), run(b)) == 0);
}
