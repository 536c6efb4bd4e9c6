// Record suites as sweep levels: the rows of a suite CSV and the files of a folder, their
// errors, and a sweep over records of different lengths and sampling intervals whose runs
// each end with their own record. Expected values come from the suite's own files (names,
// last sample times read from the .AT2 files), not from the sweep.
#include "sweep/suites.hpp"

#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "models/ground_motion.hpp"
#include "scene/records.hpp"
#include "sweep/csv.hpp"
#include "sweep/design.hpp"
#include "sweep/runner.hpp"

namespace fs = std::filesystem;
using namespace nsb::sweep;

namespace {

const fs::path kSuite = fs::path(NSB_DATA_DIR) / "ground-motions" / "asce7-suite";
const std::string kScenes = NSB_SCENES_DIR;

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("nsb_suites_test_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

std::vector<std::string> texts(const std::vector<nsb::scene::Override>& overrides) {
  std::vector<std::string> out;
  for (const auto& o : overrides) out.push_back(nsb::scene::to_string(o));
  return out;
}

std::string override_of(const std::string& key, const fs::path& file) {
  return "model.excitation." + key + "_record='" + file.lexically_normal().string() + "'";
}

}  // namespace

TEST_CASE("suite: one level per row, file_1 transverse and file_2 longitudinal by default") {
  const fs::path dir = scratch("suite");
  const fs::path design = dir / "d.toml";
  std::ofstream(design) << "scene = \"" << kScenes << "/bridge-exc5.toml\"\n"
                        << "[[factor]]\nkey = \"record\"\nsuite = \""
                        << (kSuite / "records.csv").string() << "\"\n"
                        << "[[factor]]\nkey = \"one\"\ncomponents = [\"file_2\"]\nsuite = \""
                        << (kSuite / "records.csv").string() << "\"\n";
  const Design d = load_design(design);
  REQUIRE(d.factors.size() == 2);
  // records.csv holds the 20 pairs of the suite; its first row is RSN 97, Point Mugu.
  REQUIRE(d.factors[0].levels.size() == 20);
  const Level& first = d.factors[0].levels[0];
  CHECK(first.label == "RSN97");
  CHECK(texts(first.overrides) ==
        std::vector<std::string>{override_of("transverse", kSuite / "RSN97_PTMUGU_PHN180.AT2"),
                                 override_of("longitudinal", kSuite / "RSN97_PTMUGU_PHN270.AT2")});
  CHECK(texts(d.factors[1].levels[0].overrides) ==
        std::vector<std::string>{override_of("transverse", kSuite / "RSN97_PTMUGU_PHN270.AT2")});
  CHECK(d.runs.size() == 400);
}

TEST_CASE("folder: its .AT2 files sorted by name, each a transverse record") {
  const fs::path dir = scratch("folder");
  const fs::path records = dir / "records";
  fs::create_directories(records);
  for (const char* f : {"RSN435_BORAH.MS_ANLCEAS.AT2", "RSN249_MAMMOTH.L_L-FIS000.AT2"}) {
    fs::copy_file(kSuite / f, records / f);
  }
  std::ofstream(records / "b.at2") << "";
  std::ofstream(records / "notes.txt") << "not a record";
  const auto r = read_folder(records);
  REQUIRE(r.size() == 3);
  CHECK(r[0].name == "RSN249_MAMMOTH.L_L-FIS000");
  CHECK(r[1].name == "RSN435_BORAH.MS_ANLCEAS");
  CHECK(r[2].name == "b");
  CHECK(r[0].files ==
        std::vector<std::string>{(records / "RSN249_MAMMOTH.L_L-FIS000.AT2").string()});
}

TEST_CASE("suite and folder errors name the design, the line, the key and the file") {
  const fs::path dir = scratch("errors");
  std::ofstream(dir / "s.csv") << "rsn,file_1\n1,missing.AT2\n";
  std::ofstream(dir / "dup.csv") << "name,file_1\nx,"
                                 << (kSuite / "RSN97_PTMUGU_PHN180.AT2").string() << "\nx,"
                                 << (kSuite / "RSN97_PTMUGU_PHN270.AT2").string() << "\n";
  struct Case {
    std::string body, expected;
  };
  const std::vector<Case> cases = {
      {"suite = \"s.csv\"\ncomponents = [\"file_9\"]\n",
       ":4:9: factor[0].suite: " + (dir / "s.csv").string() + ": no column \"file_9\""},
      {"suite = \"s.csv\"\ncomponents = [\"file_1\"]\n", "row 1: column file_1: no such file"},
      {"suite = \"dup.csv\"\ncomponents = [\"file_1\"]\n",
       "record name \"x\" is empty or appears twice"},
      {"folder = \".\"\ncomponents = [\"file_1\"]\n", "factor[0].components: only with suite"},
      {"folder = \"nowhere\"\n",
       "factor[0].folder: " + (dir / "nowhere").string() + ": not a folder"},
      {"suite = \"s.csv\"\ncomponents = [\"a\", \"b\", \"c\"]\n", "at most 2 columns"},
      {"suite = \"s.csv\"\nvalues = [1]\n", "give exactly one of"},
  };
  for (const auto& c : cases) {
    const fs::path file = dir / "d.toml";
    std::ofstream(file) << "scene = \"" << kScenes << "/bridge-exc5.toml\"\n[[factor]]\nkey = "
                        << "\"record\"\n"
                        << c.body;
    const std::string message = error_of([&] { (void)load_design(file); });
    INFO(c.body);
    CHECK(message.find(file.string()) == 0);
    CHECK(message.find(c.expected) != std::string::npos);
  }
}

TEST_CASE("a sweep over 3 suite records: rows name the records, each run ends with its record") {
  // Records of different lengths and sampling intervals (records.csv: npts x dt_s):
  // RSN249 2300 x 0.005 s, RSN430 1179 x 0.01 s, RSN435 1215 x 0.02 s.
  const fs::path dir = scratch("run");
  std::ofstream(dir / "three.csv")
      << "rsn,file_1,file_2\n"
      << "249," << (kSuite / "RSN249_MAMMOTH.L_L-FIS000.AT2").string() << ","
      << (kSuite / "RSN249_MAMMOTH.L_L-FIS090.AT2").string() << "\n"
      << "430," << (kSuite / "RSN430_SMART1.25_25M01EW.AT2").string() << ","
      << (kSuite / "RSN430_SMART1.25_25M01NS.AT2").string() << "\n"
      << "435," << (kSuite / "RSN435_BORAH.MS_ANLCEAS.AT2").string() << ","
      << (kSuite / "RSN435_BORAH.MS_ANLCSOU.AT2").string() << "\n";
  // The benchmark scene without its fixed end_time: a bridge then runs to the end of its
  // longest support motion (docs/scenes.md), which each record must set. Its own records are
  // named by absolute path, so that the copy loads from any working folder.
  std::ifstream in(kScenes + "/bridge-exc5.toml");
  std::ostringstream scene;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("end_time", 0) == 0) continue;
    if (const auto at = line.find("\"ground-motions/"); at != std::string::npos) {
      line.insert(at + 1, std::string(NSB_DATA_DIR) + "/");
    }
    scene << line << "\n";
  }
  std::ofstream(dir / "bridge.toml") << scene.str();
  std::ofstream(dir / "d.toml") << "scene = \"bridge.toml\"\n"
                                << "set = [\"solver.step=1e-3\", \"output.sample_dt=0.05\"]\n"
                                << "[[factor]]\nkey = \"record\"\nsuite = \"three.csv\"\n";
  SweepOptions o;
  o.out = dir / "out";
  o.jobs = 2;
  o.progress = false;
  const SweepSummary s = run_sweep(dir / "d.toml", o);
  CHECK(s.runs == 3);
  const Table t = read_csv(o.out / "results.csv");
  REQUIRE(t.rows.size() == 3);
  const char* names[] = {"RSN249", "RSN430", "RSN435"};
  const char* files[] = {"RSN249_MAMMOTH.L_L-FIS000.AT2", "RSN430_SMART1.25_25M01EW.AT2",
                         "RSN435_BORAH.MS_ANLCEAS.AT2"};
  for (std::size_t r = 0; r < 3; ++r) {
    INFO(names[r]);
    CHECK(t.rows[r][t.column("record")] == names[r]);
    CHECK(t.rows[r][t.column("status")] == "completed");
    // Both components of a pair share their length: the run ends at the last sample.
    const double last = nsb::scene::read_at2(kSuite / files[r]).t.back();
    CHECK(std::stod(t.rows[r][t.column("end_time")]) == doctest::Approx(last).epsilon(1e-12));
  }
}
