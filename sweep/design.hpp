// Sweep designs: a base scene, overrides applied to every run, and factors, read from a TOML
// file (docs/sweep.md) and expanded into the list of runs. Each run is a list of typed scene
// overrides (scene::Override: a key and its value as the design holds it, a number stays a
// double), applied to the base scene's table, which the design reads once.
//
//   Design d = load_design("scenes/sweeps/fig6.toml");   // parse, expand, read the base scene
//   validate_design(d);                                    // every key and value, before any run
//
// Errors throw std::invalid_argument with "<file>:<line>:<col>: <key>: <what is allowed>".
#pragma once

#include "scene/scene.hpp"
#include "sweep/limit_states.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace nsb::sweep {

// How the factors become runs.
enum class Mode {
  kGrid,   // full factorial: every combination of every factor's levels, first factor slowest
  kLatin,  // Latin hypercube: `samples` runs, each factor stratified into `samples` equal parts
  kList,   // the runs are the rows of a CSV file
  kOat,    // one factor at a time: the base scene, then each level of each factor alone
};
std::string_view to_string(Mode m);

// The type of a value: a factor level's, a results.csv column's.
enum class ValueKind { kReal, kInteger, kBoolean, kText };

// One level of a factor: the text that names it in results.csv and the overrides it applies.
struct Level {
  std::string label;                      // e.g. "0.5", or a record's name
  std::vector<scene::Override> overrides;  // e.g. {{"model.seats.friction", 0.5}}
  std::optional<ValueKind> kind{};     // a `values` entry's or a range's TOML type; none for
                                       //   a name (its label's text says: sweep/results.hpp)
};

struct Factor {
  std::string key;                             // column of results.csv: the scene key, or a name
  std::vector<Level> levels;                   // the levels (empty for a continuous latin range)
  std::optional<std::array<double, 2>> range;  // latin only: continuous [low, high]
  int line = 0;                                // line of its [[factor]] table in the design file
};

// One run: the label of every factor (empty when the factor keeps the base scene's value,
// as in the base run of a one-factor-at-a-time design) and every override to apply.
struct Run {
  std::string id;                          // zero-padded index: the folder name under runs/
  std::vector<std::string> labels;         // one per Design::factors entry
  std::vector<scene::Override> overrides;  // Design::set, then the factors' overrides
};

// A file the runs read (the base scene, a ground-motion record) and a hash of its bytes.
struct Input {
  std::string name;            // its path relative to the design's folder ('/' separators)
  std::filesystem::path path;  // where the runs find it
  std::string hash;            // content_hash of its bytes
};

// The design's [output] section: what `nsbridge sweep --hdf5` keeps of each run's history in
// DIR/sweep.h5 (docs/outputs.md, "sweep.h5"). It changes no run and no CSV file, so it is not
// part of the design's hash.
struct OutputSpec {
  enum class History {
    kAll,      // every column of history.csv (the default)
    kNone,     // no history: events, summary and row only
    kColumns,  // the columns listed in `columns`
  };
  History history = History::kAll;  // output.hdf5_history: "all", "none" or a list of columns
  std::vector<std::string> columns;  // kColumns: history.csv column names, `t` always kept
  int line = 0;                      // line of output.hdf5_history in the design file; 0: absent
};

struct Design {
  std::filesystem::path file;    // the design file
  std::filesystem::path scene;       // the base scene, resolved against the design's folder
  std::vector<scene::Override> set;  // overrides applied to every run
  Mode mode = Mode::kGrid;
  std::int64_t samples = 0;     // latin: number of runs, >= 1
  std::uint64_t seed = 0;       // latin: seed of the permutations
  std::vector<Factor> factors;  // in file order (list mode: one per CSV column)
  std::vector<Run> runs;        // the expanded runs, in id order
  scene::SceneTable base;                // the base scene's table as its file holds it (no
                                         //   override applied), read once: load_base_scene
  std::vector<std::string> coordinates;  // the generalized coordinates of the base scene with
                                         //   `set` ({"x", "y", "theta"} for the bridge)
  std::vector<Input> inputs;             // the base scene, then every record file a run reads,
                                         //   by name
  std::string hash;  // 16 hex digits; changes whenever a run would change: the runs' labels
                     //   and overrides and the content of every input
  std::string cross_check;  // `cross_check`: every run is cross-checked under this method
                            //   (runs::RunRequest::cross_check); empty: none
  std::optional<FragilitySpec> fragility;  // the [fragility] section, when the design has one;
                                           //   not part of the hash (it changes no run)
  OutputSpec output;                       // the [output] section; not part of the hash either
};

// Reads and expands a design file. Throws std::invalid_argument naming the file, line and key
// for a malformed design (unknown key, empty factor, duplicate key, bad range, bad CSV).
// extra_set: overrides appended to the file's `set` (the command line's --set), e.g. a short
// end_time for a quick look.
Design load_design(const std::filesystem::path& file,
                   const std::vector<std::string>& extra_set = {});

// Reads the base scene file (design.scene) once into design.base and hashes its bytes, builds
// it with `set` for design.coordinates, finds every record file the runs read
// (design.inputs, each hashed) and sets design.hash. load_design calls it; a design built in
// code calls it once its file, scene, set and runs are in place. Throws std::invalid_argument
// "<design>: scene: <the scene's message>" for a base scene that cannot be read or built with
// `set`.
void load_base_scene(Design& design);

// Builds the base scene's table (design.base, no file read) with `set` and once with each
// level of each factor (for a latin range: both ends), so that an unknown key or a value the
// scene rejects is reported before any run. Throws std::invalid_argument naming the design
// file, the factor's line and key, and the scene's own message.
void validate_design(const Design& design);

// The generalized coordinates of the design's base scene (with its `set`), as its system names
// them: design.coordinates, one peak column of results.csv each.
const std::vector<std::string>& base_coordinates(const Design& design);

// Overrides from their texts "section.key=value" (scene::parse_override's rule). Throws
// std::invalid_argument naming the text that is not one.
std::vector<scene::Override> parse_overrides(const std::vector<std::string>& texts);

// A hash of bytes: 64-bit FNV-1a (Fowler, Noll & Vo; offset basis 0xcbf29ce484222325, prime
// 0x100000001b3), as 16 hex digits. A fingerprint that notices a changed input, not a security
// measure.
std::string content_hash(std::string_view bytes);

// The unit draws of a Latin hypercube (McKay, Beckman & Conover 1979), as `mode = "latin"`
// uses them: draw[k][i] in [0, 1) for factor k and sample i. Each factor's [0, 1) is cut into
// `samples` equal strata; a Fisher–Yates permutation (std::mt19937_64 seeded with `seed`, whose
// sequence the standard fixes) gives each sample one stratum, and the draw is uniform inside
// it. The same arguments give the same draws on every platform.
std::vector<std::vector<double>> latin_hypercube(std::size_t samples, std::size_t factors,
                                                 std::uint64_t seed);

}  // namespace nsb::sweep
