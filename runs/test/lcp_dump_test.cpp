// Tests of `--dump-lcp` (runs/lcp_dump.hpp) on shipped scenes: every contact problem of a run
// is one file that reads back, whose LCP Lemke solves with the status the run recorded, and
// the manifest has one row per solve of summary.json's lcp_solves; dumping changes nothing in
// the run; a folder that cannot be made is refused before any integration.
#include "runs/files.hpp"
#include "runs/lcp_dump.hpp"
#include "runs/run.hpp"

#include "integrators/run.hpp"
#include "io/csv.hpp"
#include "lcp/lemke.hpp"
#include "lcp/siconos_format.hpp"

#include <doctest/doctest.h>

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <utility>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace nsb::runs {
namespace {

const std::string kScenes = NSB_SCENES_DIR;

std::filesystem::path temp_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("nsb-lcp-dump-" + name + "-" + std::to_string(static_cast<long>(::getpid())));
  std::filesystem::remove_all(dir);
  return dir;
}

// The manifest's rows as maps column -> field.
std::vector<std::map<std::string, std::string>> read_manifest(const std::filesystem::path& dir) {
  std::ifstream in(dir / "manifest.csv");
  std::string line;
  std::getline(in, line);
  CHECK(line == LcpDump::kManifestHeader);
  const std::vector<std::string> header = io::csv_fields(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> fields = io::csv_fields(line);
    REQUIRE(fields.size() == header.size());
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size(); ++i) row[header[i]] = fields[i];
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

TEST_CASE("a bridge run's dump: one file per solve, each read back and solved as recorded") {
  // Excitation 7 closes its first contacts at t = 3.96 s and two at once at 8.19 s: to 8.3 s,
  // some 3100 step problems with one and two contacts.
  const auto dir = temp_dir("exc7");
  RunRequest request{kScenes + "/bridge-exc7.toml", {"solver.end_time=8.3"}, "moreau", {}, dir};
  const RunRecord r = execute(request);
  REQUIRE(integrators::succeeded(r.result.status));
  const auto rows = read_manifest(dir);
  REQUIRE(r.result.lcp_solves > 100);
  CHECK(static_cast<std::int64_t>(rows.size()) == r.result.lcp_solves);
  const std::string solves = "\"lcp_solves\": " + std::to_string(rows.size()) + ",";
  CHECK(summary_json(r).find(solves) != std::string::npos);
  int two_contacts = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto& row = rows[k];
    INFO("row " << k + 1 << ": " << row.at("file"));
    CHECK(row.at("kind") == "step");
    CHECK(row.at("stage_status") == "solved");
    const lcp::Problem p = lcp::read_siconos_lcp(dir / row.at("file"));
    CHECK(std::to_string(p.size()) == row.at("size"));
    CHECK(p.size() == 3 * std::stoi(row.at("contacts")));  // frictional: eq. (6) is 3m
    two_contacts += row.at("contacts") == "2";
    if (row.at("solver") != "lemke") continue;
    const lcp::Result lemke = lcp::lemke(p);
    CHECK(std::string(lcp::to_string(lemke.status)) == row.at("status"));
  }
  CHECK(two_contacts > 0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("event-driven runs dump impact and continuous problems; the run is unchanged") {
  // Excitation 7 to 4.6 s: impacts of one contact, continuous problems after them.
  const auto dir = temp_dir("exc7-event");
  const std::string scene = kScenes + "/bridge-exc7.toml";
  const RunRecord plain = execute({scene, {"solver.end_time=4.6"}, "event_driven", {}});
  const RunRecord dumped = execute({scene, {"solver.end_time=4.6"}, "event_driven", {}, dir});
  const auto rows = read_manifest(dir);
  CHECK(static_cast<std::int64_t>(rows.size()) == dumped.result.lcp_solves);
  std::map<std::string, int> kinds;
  for (const auto& row : rows) {
    ++kinds[row.at("kind")];
    CHECK(lcp::read_siconos_lcp(dir / row.at("file")).size() == std::stoi(row.at("size")));
  }
  CHECK(kinds["impact"] > 0);
  CHECK(kinds["continuous"] > 0);
  // The observer only looks: the same steps, solves and history, bit for bit.
  CHECK(dumped.result.steps == plain.result.steps);
  CHECK(dumped.result.lcp_solves == plain.result.lcp_solves);
  REQUIRE(dumped.history.rows() == plain.history.rows());
  int differences = 0;
  for (std::size_t i = 0; i < plain.history.rows(); ++i) {
    for (std::size_t j = 0; j < plain.history.columns().size(); ++j) {
      differences += dumped.history.at(i, j) != plain.history.at(i, j);
    }
  }
  CHECK(differences == 0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("an interrupted run is a status of its own and leaves no dump") {
  // The stop request comes from the progress callback once the run is past excitation 7's
  // first contacts (3.96 s), so problems were written beside the folder when it is read.
  const auto dir = temp_dir("stopped");
  std::atomic<bool> stop{false};
  RunRequest request{kScenes + "/bridge-exc7.toml", {"solver.end_time=8.3"}, "moreau",
                     [&stop](double t) { stop.store(stop.load() || t > 4.5); }, dir};
  request.stop = &stop;
  const RunRecord r = execute(request);
  CHECK(r.result.status == integrators::RunStatus::kInterrupted);
  CHECK(r.result.message == "interrupted");
  CHECK(r.result.lcp_solves > 0);
  // Read at the progress report that set it (every 4096 steps of 1e-4 s: 0.41 s apart).
  CHECK(r.result.end_time > 4.5);
  CHECK(r.result.end_time < 4.5 + 4096 * 1e-4 + 1e-9);
  CHECK(r.result.failure_time == r.result.end_time);
  CHECK(!integrators::is_result(r.result.status));
  CHECK(!std::filesystem::exists(dir));
  int beside = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.parent_path()))
    beside += e.path().filename().string().find(dir.filename().string() + ".tmp") != std::string::npos;
  CHECK(beside == 0);
}

TEST_CASE("every method reads the stop request at every accepted step") {
  // Set before the run: each method stops after its first accepted step
  // (integrators/run_bookkeeping.hpp), long before excitation 7's 40 s.
  for (const char* method : {"moreau", "event_driven", "compliance"}) {
    INFO(method);
    std::atomic<bool> stop{true};
    RunRequest request{kScenes + "/bridge-exc7.toml", {}, method, {}};
    request.stop = &stop;
    const RunRecord r = execute(request);
    CHECK(r.result.status == integrators::RunStatus::kInterrupted);
    CHECK(!r.result.completed);
    CHECK(r.result.steps == 1);
    CHECK(r.result.end_time < 40.0);
  }
}

TEST_CASE("a dump folder that cannot be made is refused before the run") {
  const auto dir = temp_dir("file");
  std::filesystem::create_directories(dir);
  const auto file = dir / "not-a-folder";
  std::ofstream(file) << "x";
  const std::string expected = "dump_lcp " + (file / "sub").string() + ": ";
  CHECK_THROWS_WITH_AS(prepare({kScenes + "/bouncing-ball.toml", {}, {}, {}, file / "sub"}),
                       doctest::Contains(expected.c_str()), std::invalid_argument);
  std::filesystem::remove_all(dir);
}

}  // namespace nsb::runs
