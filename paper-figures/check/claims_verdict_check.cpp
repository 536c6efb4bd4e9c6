// Checks the output of `nsbridge figures --quick` (CTest fixture figures_quick): every figure
// has its PNG, SVG and CSV and axis labels with units, and every verdict in claims.json follows
// from the numbers printed beside it. It does not check that a claim is true: it re-derives
// "holds" from the checks (value op threshold, all of them) with its own reading of the file
// and its own comparison, so that a verdict that contradicts its numbers fails here. For the
// uncertainty study it re-derives every sample's verdicts in uncertainty.csv from the check
// quantities beside them (with the thresholds of claims.json), the shares and their standard
// errors in uncertainty.json from those verdicts, and the flips from uncertainty-oat.csv.
#include "io/json_reader.hpp"

#include <doctest/doctest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

using Json = nsb::io::JsonValue;

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The comparison, written independently of paper-figures/claims.cpp. A missing (null,
// non-finite) value never satisfies a comparison.
bool satisfied(double v, const std::string& op, double th) {
  if (std::isnan(v) || std::isnan(th)) return false;
  if (op == "<") return v < th;
  if (op == "<=") return v <= th;
  if (op == ">") return v > th;
  if (op == ">=") return v >= th;
  FAIL("unknown op " << op);
  return false;
}

const fs::path kDir = NSB_FIGURES_DIR;

}  // namespace

TEST_CASE("every verdict in claims.json follows from its numbers") {
  const Json root = nsb::io::parse_json(read(kDir / "claims.json"));
  const Json& claims = root.at("claims");
  REQUIRE(claims.type == Json::Type::kArray);
  std::vector<std::string> ids;
  for (const Json& c : claims.items) {
    const std::string id = c.at("id").text;
    ids.push_back(id);
    CAPTURE(id);
    REQUIRE(c.at("holds").type == Json::Type::kBool);
    REQUIRE(c.at("checks").type == Json::Type::kArray);
    CHECK(!c.at("statement").text.empty());
    CHECK(!c.at("runs").items.empty());
    CHECK(!c.at("measured").keys.empty());
    const bool evaluated = c.at("reason").text.rfind("not evaluated", 0) != 0;
    bool all = evaluated && !c.at("checks").items.empty();
    for (const Json& k : c.at("checks").items) {
      CAPTURE(k.at("quantity").text);
      CHECK(!k.at("why").text.empty());
      all = all && satisfied(k.at("value").number, k.at("op").text, k.at("threshold").number);
    }
    CHECK(c.at("holds").boolean == all);
  }
  CHECK(ids == std::vector<std::string>{"C1", "C2", "C3", "C4", "C5", "C6", "C4'", "C5'"});
}

TEST_CASE("the compliance claims name their damping law and its effective restitution") {
  const Json root = nsb::io::parse_json(read(kDir / "claims.json"));
  std::map<std::string, const Json*> by_id;
  for (const Json& c : root.at("claims").items) by_id[c.at("id").text] = &c;
  const std::map<std::string, std::string> laws{{"C4", "hertzdamp"},
                                                {"C5", "hertzdamp"},
                                                {"C4'", "hunt_crossley_exact"},
                                                {"C5'", "hunt_crossley_exact"}};
  for (const auto& [id, name] : laws) {
    CAPTURE(id);
    REQUIRE(by_id.count(id) == 1);
    const Json& law = by_id[id]->at("law");
    REQUIRE(law.type == Json::Type::kObject);
    CHECK(law.at("name").text == name);
    const double chi = law.at("chi").number, e = law.at("effective_restitution").number;
    const double eps = law.at("nonsmooth_restitution").number;
    REQUIRE(std::isfinite(chi));
    REQUIRE(std::isfinite(e));
    CHECK(chi >= 0.0);
    CHECK(e >= 0.0);
    CHECK(e <= 1.0);
    CHECK(eps >= 0.0);
    CHECK(eps <= 1.0);
    // e is the restitution of a Hunt-Crossley impact with factor chi: the root of
    // 1 - chi e = (1 + chi) exp(-chi (1 + e)) (docs/compliance.md, derived there).
    CHECK(std::abs(1.0 - chi * e - (1.0 + chi) * std::exp(-chi * (1.0 + e))) < 1e-6);
    if (name == "hertzdamp") CHECK(chi == doctest::Approx(0.75 * (1.0 - eps * eps)));
    // The exact law matches the nonsmooth eps, up to its floor of 1e-3 at eps = 0.
    if (name == "hunt_crossley_exact") CHECK(std::abs(e - eps) <= 1e-3 + 1e-9);
  }
  // The primed claims judge the same quantities as their twins, side by side.
  for (const char* id : {"C4", "C5"}) {
    CAPTURE(id);
    std::vector<std::string> a, b;
    for (const Json& k : by_id[id]->at("checks").items) a.push_back(k.at("quantity").text);
    for (const Json& k : by_id[std::string(id) + "'"]->at("checks").items) {
      b.push_back(k.at("quantity").text);
    }
    CHECK(a == b);
  }
  for (const auto& [id, c] : by_id) {
    if (laws.count(id) == 0) CHECK(c->at("law").type == Json::Type::kNull);
  }
}

TEST_CASE("every figure has its PNG, SVG and CSV, and axis labels with units") {
  int figures = 0;
  for (const auto& e : fs::directory_iterator(kDir)) {
    if (e.path().extension() != ".gp") continue;
    const auto stem = e.path().stem().string();
    CAPTURE(stem);
    ++figures;
    for (const char* ext : {".png", ".svg", ".csv"}) {
      const auto p = kDir / (stem + ext);
      CHECK(fs::exists(p));
      CHECK(fs::file_size(p) > 100);
    }
    const std::string gp = read(e.path());
    for (const char* axis : {"set xlabel '", "set ylabel '"}) {
      const auto at = gp.find(axis);
      REQUIRE(at != std::string::npos);
      const auto line = gp.substr(at, gp.find('\n', at) - at);
      CAPTURE(line);
      CHECK(line.find('[') != std::string::npos);  // a unit in brackets, [-] if none
    }
  }
  CHECK(figures == 7);  // Figs. 3, 4, 5, 6, 7, 8 and the eta map
}

namespace {

// A CSV file without quoted fields (the study writes none): header and rows of fields.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::size_t col(const std::string& name) const {
    for (std::size_t k = 0; k < header.size(); ++k) {
      if (header[k] == name) return k;
    }
    FAIL("no column " << name);
    return 0;
  }
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> f;
  std::string cur;
  for (char ch : line) {
    if (ch == ',') {
      f.push_back(cur);
      cur.clear();
    } else if (ch != '\r') {
      cur += ch;
    }
  }
  f.push_back(cur);
  return f;
}

Csv read_csv(const fs::path& p) {
  std::ifstream in(p);
  REQUIRE(in);
  Csv c;
  std::string line;
  REQUIRE(std::getline(in, line));
  c.header = split(line);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    c.rows.push_back(split(line));
    REQUIRE(c.rows.back().size() == c.header.size());
  }
  return c;
}

double number(const std::string& s) {
  return s.empty() ? std::numeric_limits<double>::quiet_NaN() : std::stod(s);
}

// The checks of each claim in claims.json: quantity -> (op, threshold).
std::map<std::string, std::map<std::string, std::pair<std::string, double>>> thresholds() {
  const Json root = nsb::io::parse_json(read(kDir / "claims.json"));
  std::map<std::string, std::map<std::string, std::pair<std::string, double>>> out;
  for (const Json& c : root.at("claims").items) {
    for (const Json& k : c.at("checks").items) {
      out[c.at("id").text][k.at("quantity").text] = {k.at("op").text, k.at("threshold").number};
    }
  }
  return out;
}

// A row's verdict of claim id from its check columns "<id>.<quantity>".
bool derived(const Csv& csv, const std::vector<std::string>& row, const std::string& id,
             const std::map<std::string, std::pair<std::string, double>>& checks) {
  bool all = true;
  int seen = 0;
  for (std::size_t k = 0; k < csv.header.size(); ++k) {
    const std::string& h = csv.header[k];
    if (h.rfind(id + ".", 0) != 0) continue;
    const std::string q = h.substr(id.size() + 1);
    const auto it = checks.find(q);
    REQUIRE_MESSAGE(it != checks.end(), "no threshold in claims.json for " << h);
    all = all && satisfied(number(row[k]), it->second.first, it->second.second);
    ++seen;
  }
  CHECK(seen > 0);
  return all && seen > 0;
}

}  // namespace

TEST_CASE("the uncertainty shares and flips follow from the per-sample verdicts") {
  const auto th = thresholds();
  const Json u = nsb::io::parse_json(read(kDir / "uncertainty.json"));
  const Csv samples = read_csv(kDir / "uncertainty.csv");
  const Csv oat = read_csv(kDir / "uncertainty-oat.csv");
  REQUIRE(u.at("claims").type == Json::Type::kArray);
  CHECK(u.at("samples").number == double(samples.rows.size()));
  CHECK(!samples.rows.empty());
  for (const Json& c : u.at("claims").items) {
    const std::string id = c.at("id").text;
    CAPTURE(id);
    const std::size_t v = samples.col(id);
    std::size_t holds = 0, evaluated = 0;
    for (const auto& row : samples.rows) {
      CAPTURE(row[0]);
      if (row[v] == "not evaluated") continue;
      REQUIRE((row[v] == "holds" || row[v] == "fails"));
      ++evaluated;
      holds += row[v] == "holds";
      CHECK(derived(samples, row, id, th.at(id)) == (row[v] == "holds"));
    }
    // Share p = holds / evaluated, binomial standard error sqrt(p (1 - p) / evaluated).
    CHECK(c.at("samples").number == double(evaluated));
    CHECK(c.at("holds").number == double(holds));
    if (evaluated > 0) {
      const double p = double(holds) / double(evaluated);
      CHECK(c.at("share").number == doctest::Approx(p).epsilon(1e-12));
      CHECK(c.at("standard_error").number ==
            doctest::Approx(std::sqrt(p * (1 - p) / double(evaluated))).epsilon(1e-12));
    }
    // Flips: the one-at-a-time points whose verdict differs from the base point's.
    const std::size_t ov = oat.col(id), oa = oat.col("assumption"), oe = oat.col("end");
    std::string base;
    for (const auto& row : oat.rows) {
      if (row[oa].empty()) base = row[ov];
      if (row[ov] != "not evaluated") {
        CHECK(derived(oat, row, id, th.at(id)) == (row[ov] == "holds"));
      }
    }
    // --quick judges no one-at-a-time point: then there is nothing to flip.
    REQUIRE((!base.empty() || oat.rows.empty()));
    std::set<std::string> expected, written;
    for (const auto& row : oat.rows) {
      if (row[oa].empty() || base == "not evaluated" || row[ov] == "not evaluated") continue;
      if (row[ov] != base) expected.insert(row[oa] + " " + row[oe]);
    }
    for (const Json& f : c.at("flips").items) {
      written.insert(f.at("assumption").text + " " + f.at("end").text);
    }
    CHECK(expected == written);
  }
  for (const char* ext : {".png", ".svg", ".csv"}) {
    const auto p = kDir / (std::string("uncertainty-tornado") + ext);
    CHECK(fs::exists(p));
    CHECK(fs::file_size(p) > 100);
  }
}
