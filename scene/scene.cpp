#include "scene/scene.hpp"

#include "scene/scene_builders.hpp"
#include "scene/scene_reader.hpp"

#include <toml++/toml.h>

#include <cerrno>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace nsb::scene {

using namespace models;  // the systems and parts a scene builds

namespace {

namespace fs = std::filesystem;

// The parsed TOML of a scene file; a syntax error names its line and column.
toml::table parse_scene_file(const fs::path& file, const Source& ctx) {
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (!fs::exists(status)) {
    throw std::invalid_argument(ctx.file + ": cannot open scene file (not found)");
  }
  if (!fs::is_regular_file(status)) {
    // A FIFO or a device could block or never end; a directory holds no text.
    throw std::invalid_argument(ctx.file + ": cannot open scene file (not a regular file)");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in.is_open()) {
    throw std::invalid_argument(ctx.file + ": cannot read scene file (" +
                                std::generic_category().message(errno) + ")");
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) {
    throw std::invalid_argument(ctx.file + ": cannot read scene file (a read error)");
  }
  try {
    return toml::parse(text.str(), file.string());
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << ctx.file << ':' << e.source().begin.line << ':' << e.source().begin.column
      << ": TOML syntax error: " << e.description();
    throw std::invalid_argument(s.str());
  }
}

// [model] kind, which must be present.
// [output] groups: an array of group names (or, from an override, one string of names
// separated by commas), checked against integrators::kOutputGroupNames; the canonical list.
std::string read_output_groups(const Section& output) {
  const toml::node* node = output.table().get("groups");
  if (node == nullptr) return {};
  std::string list;
  if (const toml::array* a = node->as_array()) {
    for (const toml::node& e : *a) {
      const auto name = e.value<std::string>();
      if (!name) output.fail("groups", "must be an array of group names (strings)");
      list += (list.empty() ? "" : ",") + *name;
    }
  } else if (const auto text = node->value<std::string>()) {
    list = *text;
  } else {
    output.fail("groups", "must be an array of group names (strings)");
  }
  try {
    return integrators::OutputGroups::parse(list).names();
  } catch (const std::invalid_argument& e) {
    output.fail("groups", e.what());
  }
}

std::string read_kind(const Section& m) {
  if (!m.has("kind")) {
    std::string list;
    for (const auto& k : scene_kinds()) list += (list.empty() ? "" : ", ") + k;
    m.fail_table("missing key kind (one of " + list + ")");
  }
  SceneHeader header;
  m.read(*config::find_field(SceneHeader::fields(), "kind"), header);
  return header.kind;
}

// Sets the final time of a run to t.
void set_end_time(integrators::RunConfig& run, double t) {
  std::visit([t](auto& o) { o.end_time = t; }, run);
}

}  // namespace

SceneTable read_scene_table(const std::filesystem::path& file) {
  SceneTable scene;
  scene.origin.name = file.string();
  scene.origin.folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  Source ctx;
  ctx.file = scene.origin.name;
  scene.table = parse_scene_file(file, ctx);
  return scene;
}

std::string to_toml(const SceneTable& scene) {
  std::ostringstream s;
  s << toml::toml_formatter(scene.table) << '\n';
  return s.str();
}

Scene build_scene(const SceneTable& source) {
  Source ctx;
  ctx.file = source.origin.name;
  ctx.dir = source.origin.folder;
  ctx.overridden = source.overridden;
  const toml::table& root = source.table;

  Scene scene;
  scene.path = source.origin.name;
  scene.name = scene.path.stem().string();
  Section top(ctx, root, "");
  top.only({"description", "model", "solver", "output"});
  SceneHeader header;
  top.read(*config::find_field(SceneHeader::fields(), "description"), header);
  const toml::table* model = top.subtable("model");
  if (model == nullptr) top.fail_table("missing table [model]");
  const toml::table no_table;
  const toml::table* solver_table = top.subtable("solver");
  Section solver(ctx, solver_table != nullptr ? *solver_table : no_table, "solver");
  Section output(ctx, top.subtable("output") != nullptr ? *top.subtable("output") : no_table,
                 "output");

  Section m(ctx, *model, "model");
  scene.kind = read_kind(m);
  scene.run = read_solver(solver, scene.estimate);
  output.only(keys_of(OutputSettings::fields()));
  for (const auto& f : OutputSettings::fields()) {
    if (f.key != "groups") output.read(f, scene.output);
  }
  scene.output.groups = read_output_groups(output);

  if (scene.kind == "bridge") {
    BridgeScene bridge = build_bridge(m);
    scene.system = std::move(bridge.system);
    scene.design = std::move(bridge.design);
    scene.input = bridge.input;
    if (!solver.has("end_time") && bridge.motion_end > 0) set_end_time(scene.run, bridge.motion_end);
    // Every record of a scene shares the excitation's time_scale.
    scene.record_step = ctx.record_step * bridge.time_scale;
  } else if (scene.kind == "rigid_deck") {
    BridgeScene deck = build_rigid_deck(m);
    scene.system = std::move(deck.system);
    scene.design = std::move(deck.design);
  } else if (scene.kind == "deck_chain") {
    scene.system = build_deck_chain(m);
  } else {
    scene.system = build_simple_system(scene.kind, m);
  }
  check_solver(solver, scene.run);
  check_work(solver, output, scene.run, scene.system->initial_time(), scene.output.sample_dt);
  scene.table = source;
  return scene;
}

Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  SceneTable source = read_scene_table(file);
  apply_overrides(source, overrides);
  return build_scene(source);
}

}  // namespace nsb::scene
