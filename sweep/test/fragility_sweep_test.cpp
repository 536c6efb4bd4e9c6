// Fragility from a sweep: the [fragility] section read with the design (every error names the
// file, line and key), the stripes counted from a results table, the fits equal to
// sweep/fragility's on the same stripes, the IDA capacities by hand, and fragility.json
// without NaN for data that have no estimate.
#include "sweep/fragility_sweep.hpp"

#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace nsb::sweep;

namespace {

const std::string kScenes = NSB_SCENES_DIR;

fs::path write_design(const std::string& name, const std::string& body) {
  const fs::path dir =
      fs::temp_directory_path() / ("nsb_fragility_sweep_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / (name + ".toml");
  std::ofstream(file) << body;
  return file;
}

// A grid over the bouncing ball: restitution (the IM stand-in) x gravity, then `fragility`.
std::string design_text(const std::string& fragility) {
  return "scene = \"" + kScenes + "/bouncing-ball.toml\"\n" + R"(set = ["solver.end_time=1"]
[[factor]]
key = "model.restitution"
values = [0.5, 0.9]
[[factor]]
key = "model.gravity"
values = [9.81, 4.905]
)" + fragility;
}

std::string error_of(const std::string& name, const std::string& fragility) {
  try {
    (void)load_design(write_design(name, design_text(fragility)));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

const std::string kLimit = R"(
[[fragility.limit_state]]
name = "high"
response = "peak_y"
threshold = 1.0
)";

// A results table with the columns of a sweep: run, the factors (im, record), status, the
// response. rows: {im, record, status, response}.
Table results(const std::vector<std::vector<std::string>>& rows) {
  Table t;
  t.header = {"run", "im", "record", "status", "peak_theta", "residual_theta", "message"};
  int id = 0;
  for (const auto& r : rows) {
    t.rows.push_back({std::to_string(id++), r[0], r[1], r[2], r[3], r.size() > 4 ? r[4] : "0", ""});
  }
  return t;
}

FragilitySpec spec(double threshold, const std::string& response = "peak_theta",
                   bool absolute = false) {
  return {"im", {{"ls", response, threshold, absolute}}};
}

}  // namespace

TEST_CASE("[fragility] is read with the design: the IM factor and the limit states") {
  const Design d = load_design(write_design("good", design_text(R"(
[fragility]
im = "model.restitution"
[[fragility.limit_state]]
name = "a"
response = "peak_y"
threshold = 2
[[fragility.limit_state]]
name = "b"
response = "residual_y"
threshold = -0.5
absolute = true
)")));
  REQUIRE(d.fragility.has_value());
  CHECK(d.fragility->im == "model.restitution");
  REQUIRE(d.fragility->limit_states.size() == 2);
  CHECK(d.fragility->limit_states[0].name == "a");
  CHECK(d.fragility->limit_states[0].threshold == 2.0);
  CHECK_FALSE(d.fragility->limit_states[0].absolute);
  CHECK(d.fragility->limit_states[1].response == "residual_y");
  CHECK(d.fragility->limit_states[1].absolute);
  CHECK(is_ida(d, "model.restitution"));
  // The section changes no run: the same design without it has the same hash.
  CHECK(load_design(write_design("plain", design_text(""))).hash == d.hash);
  CHECK_FALSE(load_design(write_design("plain", design_text(""))).fragility.has_value());
}

TEST_CASE("bad [fragility] input names the file, line, column and key") {
  const auto e1 =
      error_of("unknown", "[fragility]\nim = \"model.restitution\"\ncolour = 1\n" + kLimit);
  CHECK(e1.find("unknown.toml:11:10: fragility.colour: unknown key") != std::string::npos);
  const auto e2 = error_of("im", "[fragility]\nim = \"model.mass\"\n" + kLimit);
  CHECK(e2.find("im.toml:10:6: fragility.im: \"model.mass\" is not a factor of the design "
                "(factors: \"model.restitution\", \"model.gravity\")") != std::string::npos);
  const auto e3 = error_of("noim", "[fragility]\n" + kLimit);
  CHECK(e3.find("noim.toml:9:1: fragility.im: required") != std::string::npos);
  const auto e4 = error_of("response", R"([fragility]
im = "model.restitution"
[[fragility.limit_state]]
name = "x"
response = "peak_theta"
threshold = 1
)");
  CHECK(e4.find("response.toml:13:12: fragility.limit_state[0].response: \"peak_theta\" is not "
                "a results.csv column of this design (allowed: peak_y, peak_y_error, residual_y,") !=
        std::string::npos);
  for (const std::string bad : {"nan", "inf", "\"1\""}) {
    const auto e = error_of("threshold", "[fragility]\nim = \"model.restitution\"\n"
                            "[[fragility.limit_state]]\nname = \"x\"\nresponse = \"peak_y\"\n"
                            "threshold = " + bad + "\n");
    CHECK(e.find("threshold.toml:14:13: fragility.limit_state[0].threshold: required: a finite "
                 "number") != std::string::npos);
  }
  const auto e5 = error_of("twice", "[fragility]\nim = \"model.restitution\"\n" + kLimit + kLimit);
  CHECK(e5.find("fragility.limit_state[1].name: \"high\" appears twice") != std::string::npos);
  const auto e6 = error_of("none", "[fragility]\nim = \"model.restitution\"\n");
  CHECK(e6.find("none.toml:9:1: fragility.limit_state: required") != std::string::npos);
  const auto e7 = error_of("extra", "[fragility]\nim = \"model.restitution\"\n" + kLimit +
                                        "absolute = 1\n");
  CHECK(e7.find("fragility.limit_state[0].absolute: must be true or false") != std::string::npos);
}

TEST_CASE("an IM factor whose levels are not numbers > 0 is refused") {
  const std::string body = "scene = \"" + kScenes + "/bouncing-ball.toml\"\n" + R"(
[[factor]]
key = "shape"
levels = [ { name = "low", set = ["model.restitution=0.5"] } ]
[fragility]
im = "shape"
)" + kLimit;
  std::string e;
  try {
    (void)load_design(write_design("levels", body));
  } catch (const std::invalid_argument& x) {
    e = x.what();
  }
  CHECK(e.find("levels.toml:7:6: fragility.im: factor \"shape\" has the level \"low\": the "
               "stripes' levels must be numbers > 0") != std::string::npos);
}

TEST_CASE("stripes counted by hand; the fit is fit_mle's on the same stripes") {
  // 3 stripes x 4 records; response >= 0.01 exceeds (the threshold itself exceeds).
  const Table t = results({
      {"0.2", "a", "completed", "0.001"}, {"0.2", "b", "completed", "0.02"},
      {"0.2", "c", "completed", "0.003"}, {"0.2", "d", "completed", "0.004"},
      {"0.5", "a", "completed", "0.01"},  {"0.5", "b", "completed", "0.03"},
      {"0.5", "c", "completed", "0.002"}, {"0.5", "d", "completed", "0.009"},
      {"1", "a", "completed", "0.05"},    {"1", "b", "completed", "0.04"},
      {"1", "c", "completed_with_fallbacks", "0.02"}, {"1", "d", "completed", "0.008"},
  });
  const FragilityReport r = fit_fragility(spec(0.01), results_of(t), false);
  REQUIRE(r.fits.size() == 1);
  const auto& s = r.fits[0].stripes;
  REQUIRE(s.size() == 3);
  CHECK(s[0].im == 0.2);
  CHECK(s[0].n == 4);
  CHECK(s[0].exceeded == 1);
  CHECK(s[1].im == 0.5);
  CHECK(s[1].exceeded == 2);
  CHECK(s[2].im == 1.0);
  CHECK(s[2].exceeded == 3);
  const FragilityFit direct = fit_mle({{0.2, 4, 1}, {0.5, 4, 2}, {1.0, 4, 3}});
  REQUIRE(direct.status == FitStatus::kFitted);
  CHECK(r.fits[0].mle.status == FitStatus::kFitted);
  CHECK(r.fits[0].mle.theta == direct.theta);
  CHECK(r.fits[0].mle.beta == direct.beta);
  CHECK(r.fits[0].mle.ci95_theta == direct.ci95_theta);
  CHECK(r.fits[0].mle.ci95_beta == direct.ci95_beta);
  CHECK_FALSE(r.fits[0].moments.has_value());
}

TEST_CASE("runs that did not complete are left out of n and counted as left_out") {
  const Table t = results({
      {"0.2", "a", "completed", "0.001"}, {"0.2", "b", "diverged", ""},
      {"0.5", "a", "completed", "0.02"},  {"0.5", "b", "rejected", ""},
      {"1", "a", "stalled", "0.5"},       {"1", "b", "contact_unsolved", "0.5"},
      {"", "c", "completed", "0.5"},  // no IM (an empty label): no stripe
  });
  const FragilityReport r = fit_fragility(spec(0.01), results_of(t), false);
  const auto& s = r.fits[0].stripes;
  REQUIRE(s.size() == 3);
  CHECK((s[0].n == 1 && s[0].exceeded == 0 && s[0].left_out == 1));
  CHECK((s[1].n == 1 && s[1].exceeded == 1 && s[1].left_out == 1));
  CHECK((s[2].n == 0 && s[2].exceeded == 0 && s[2].left_out == 2));
  // The stripe without a completed run is not fitted: 2 stripes, separated data.
  CHECK(r.fits[0].mle.stripes.size() == 2);
  CHECK(r.fits[0].mle.status == FitStatus::kSeparated);
}

TEST_CASE("absolute compares |response| with the threshold") {
  const Table t = results({{"0.2", "a", "completed", "0", "-0.02"},
                           {"0.2", "b", "completed", "0", "0.001"}});
  CHECK(fit_fragility(spec(0.01, "residual_theta"), results_of(t), false).fits[0].stripes[0].exceeded == 0);
  CHECK(fit_fragility(spec(0.01, "residual_theta", true), results_of(t), false).fits[0].stripes[0].exceeded ==
        1);
}

TEST_CASE("no exceedance: null theta, beta and bands with the status, never NaN") {
  const Table t = results({{"0.2", "a", "completed", "0.001"}, {"0.5", "a", "completed", "0.002"},
                           {"1", "a", "completed", "0.003"}});
  const FragilityReport r = fit_fragility(spec(0.01), results_of(t), true);
  CHECK(r.fits[0].mle.status == FitStatus::kNoExceedances);
  const std::string json = fragility_json(r);
  CHECK(json.find("\"status\": \"no_exceedances\"") != std::string::npos);
  CHECK(json.find("\"theta\": null, \"beta\": null") != std::string::npos);
  CHECK(json.find("\"ci95_theta\": null, \"ci95_beta\": null") != std::string::npos);
  CHECK(json.find("nan") == std::string::npos);
  CHECK(json.find("\"moments\": {\"status\": \"censored\"") != std::string::npos);
  // No curve to draw: the points alone, titled with the status.
  const std::string script = fragility_script(r);
  CHECK(script.find("$curve0") == std::string::npos);
  CHECK(script.find("ls: no_exceedances") != std::string::npos);
}

TEST_CASE("IDA: each record's capacity is its lowest IM that reaches the limit state") {
  // Record a reaches 0.01 at 0.5 (and again at 1), b at 1, c at 0.2; d's run at 0.5 diverged
  // and is skipped, so its capacity is 1.
  const Table t = results({
      {"0.2", "a", "completed", "0.001"}, {"0.5", "a", "completed", "0.02"},
      {"1", "a", "completed", "0.03"},    {"0.2", "b", "completed", "0.001"},
      {"0.5", "b", "completed", "0.002"}, {"1", "b", "completed", "0.01"},
      {"0.2", "c", "completed", "0.05"},  {"0.5", "c", "completed", "0.002"},
      {"1", "c", "completed", "0.04"},    {"0.2", "d", "completed", "0.001"},
      {"0.5", "d", "diverged", ""},       {"1", "d", "completed", "0.02"},
  });
  const FragilityReport r = fit_fragility(spec(0.01), results_of(t), true);
  REQUIRE(r.fits[0].moments.has_value());
  const MomentsFit& m = *r.fits[0].moments;
  const FragilityFit direct = fit_moments({0.5, 1.0, 0.2, 1.0});
  CHECK(m.status == "fitted");
  CHECK(m.records == 4);
  CHECK(m.censored == 0);
  CHECK(m.theta == direct.theta);
  CHECK(m.beta == direct.beta);
  // A record that never reaches the limit state: censored, no moments.
  const FragilityReport c = fit_fragility(spec(0.025), results_of(t), true);
  CHECK(c.fits[0].moments->status == "censored");
  CHECK(c.fits[0].moments->censored == 2);
  CHECK(c.fits[0].moments->theta == 0.0);
  CHECK(fragility_json(c).find("\"theta\": null, \"beta\": null, \"records\": 4, "
                               "\"censored\": 2") != std::string::npos);
}

TEST_CASE("results without the IM or the response column") {
  const Table t = results({{"0.2", "a", "completed", "0.001"}});
  CHECK_THROWS_WITH_AS(fit_fragility({"pga", {{"ls", "peak_theta", 1.0, false}}}, results_of(t), false),
                       "fragility.im: results.csv has no column \"pga\"", std::invalid_argument);
  CHECK_THROWS_WITH_AS(fit_fragility(spec(1.0, "peak_x"), results_of(t), false),
                       "fragility.limit_state ls: results.csv has no column \"peak_x\"",
                       std::invalid_argument);
}

TEST_CASE("limit_state names a watched limit state: its _exceeded column, threshold 1") {
  const Design d = load_design(write_design("watched", design_text(R"(
[fragility]
im = "model.restitution"
unseated = "response"
[[fragility.limit_state]]
limit_state = "unseating_left"
[[fragility.limit_state]]
name = "drift"
limit_state = "drift_bent_2"
unseated = "exceeded"
)")));
  REQUIRE(d.fragility->limit_states.size() == 2);
  const LimitState& a = d.fragility->limit_states[0];
  CHECK(a.name == "unseating_left");  // the name defaults to the watched limit state's
  CHECK(a.watched == "unseating_left");
  CHECK(a.response == "unseating_left_exceeded");
  CHECK(a.threshold == 1.0);
  CHECK((!a.absolute && !a.below));
  CHECK(a.unseated == UnseatedRuns::kResponse);  // the section's default
  CHECK(d.fragility->limit_states[1].name == "drift");
  CHECK(d.fragility->limit_states[1].response == "drift_bent_2_exceeded");
  CHECK(d.fragility->limit_states[1].unseated == UnseatedRuns::kExceed);
  const auto e1 = error_of("both", "[fragility]\nim = \"model.restitution\"\n"
                           "[[fragility.limit_state]]\nlimit_state = \"closure_left\"\n"
                           "threshold = 0.5\n");
  CHECK(e1.find("both.toml:13:13: fragility.limit_state[0].threshold: not allowed with "
                "limit_state") != std::string::npos);
  const auto e2 = error_of("empty", "[fragility]\nim = \"model.restitution\"\n"
                           "[[fragility.limit_state]]\nlimit_state = \"\"\n");
  CHECK(e2.find("empty.toml:12:15: fragility.limit_state[0].limit_state: must be the name of a "
                "watched limit state") != std::string::npos);
  const auto e3 = error_of("mode", "[fragility]\nim = \"model.restitution\"\nunseated = \"yes\"\n" +
                           kLimit);
  CHECK(e3.find("mode.toml:11:12: fragility.unseated: must be \"exceeded\"") != std::string::npos);
}

TEST_CASE("an unseated run counts in n; it reaches every limit state unless unseated = response") {
  // Stripe 0.5: a completed below the threshold, b unseated with a response below it; stripe 1:
  // a completed above it, b unseated, c diverged (left out either way).
  const Table t = results({{"0.5", "a", "completed", "0.001"},
                           {"0.5", "b", "unseated", "0.002"},
                           {"1", "a", "completed", "0.02"},
                           {"1", "b", "unseated", "0.003"},
                           {"1", "c", "diverged", ""}});
  FragilitySpec s = spec(0.01);
  const FragilityReport r = fit_fragility(s, results_of(t), false);
  const auto& st = r.fits[0].stripes;
  CHECK((st[0].n == 2 && st[0].exceeded == 1 && st[0].unseated == 1 && st[0].left_out == 0));
  CHECK((st[1].n == 2 && st[1].exceeded == 2 && st[1].unseated == 1 && st[1].left_out == 1));
  const std::string json = fragility_json(r);
  CHECK(json.find("\"absolute\": false, \"unseated\": \"exceeded\",") != std::string::npos);
  CHECK(json.find("{\"im\": 0.5, \"n\": 2, \"exceeded\": 1, \"left_out\": 0, \"unseated\": 1}") !=
        std::string::npos);
  s.limit_states[0].unseated = UnseatedRuns::kResponse;
  const FragilityReport rr = fit_fragility(s, results_of(t), false);
  const auto& sr = rr.fits[0].stripes;
  CHECK((sr[0].n == 2 && sr[0].exceeded == 0));
  CHECK((sr[1].n == 2 && sr[1].exceeded == 1));
  // Without an unseated run the JSON has no "unseated" (the files of sweeps without seats).
  CHECK(fragility_json(fit_fragility(spec(0.01), results_of(results({{"1", "a", "completed", "0.02"}})),
                                     false))
            .find("unseated") == std::string::npos);
}

TEST_CASE("a watched limit state no run watches names those the runs watch") {
  Table t = results({{"0.2", "a", "completed", "0.001"}});
  t.header.insert(t.header.end() - 1, {"closure_left_exceeded", "closure_left_margin"});
  for (auto& row : t.rows) row.insert(row.end() - 1, {"0", "0.01"});
  LimitState ls{"u", "unseating_left_exceeded", 1.0};
  ls.watched = "unseating_left";
  CHECK_THROWS_WITH_AS(fit_fragility({"im", {ls}}, results_of(t), false),
                       "fragility.limit_state u: no run of the sweep watches \"unseating_left\" "
                       "(results.csv has no column unseating_left_exceeded; watched: "
                       "closure_left)",
                       std::invalid_argument);
}
