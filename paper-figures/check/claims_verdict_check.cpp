// Checks the output of `nsbridge figures --quick` (CTest fixture figures_quick): every figure
// has its PNG, SVG and CSV and axis labels with units, and every verdict in claims.json follows
// from the numbers printed beside it. It does not check that a claim is true: it re-derives
// "holds" from the checks (value op threshold, all of them) with its own reading of the file
// and its own comparison, so that a verdict that contradicts its numbers fails here. For the
// uncertainty study it re-derives every sample's verdicts in uncertainty.csv from the check
// quantities beside them (with the thresholds of claims.json), the shares and their standard
// errors in uncertainty.json from those verdicts, and the flips from uncertainty-oat.csv.
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

// A JSON value, enough for claims.json: objects, arrays, strings, numbers, true/false/null.
struct Json {
  enum Kind { kNull, kBool, kNumber, kString, kArray, kObject } kind = kNull;
  bool b = false;
  double n = std::numeric_limits<double>::quiet_NaN();
  std::string s;
  std::vector<Json> a;
  std::map<std::string, Json> o;
  const Json& at(const std::string& k) const {
    static const Json kMissing;
    const auto it = o.find(k);
    return it == o.end() ? kMissing : it->second;
  }
};

class Parser {
 public:
  explicit Parser(std::string text) : t_(std::move(text)) {}
  Json parse() {
    Json v = value();
    ws();
    if (i_ != t_.size()) fail("trailing text");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("claims.json at " + std::to_string(i_) + ": " + what);
  }
  void ws() {
    while (i_ < t_.size() && std::isspace(static_cast<unsigned char>(t_[i_]))) ++i_;
  }
  bool eat(char c) {
    ws();
    if (i_ < t_.size() && t_[i_] == c) return ++i_, true;
    return false;
  }
  std::string str() {
    if (!eat('"')) fail("expected a string");
    std::string out;
    while (i_ < t_.size() && t_[i_] != '"') {
      if (t_[i_] == '\\' && i_ + 1 < t_.size()) {
        ++i_;
        out += t_[i_] == 'n' ? '\n' : t_[i_];
      } else {
        out += t_[i_];
      }
      ++i_;
    }
    if (!eat('"')) fail("unterminated string");
    return out;
  }
  Json value() {
    ws();
    Json v;
    if (i_ >= t_.size()) fail("unexpected end");
    const char c = t_[i_];
    if (c == '{') {
      v.kind = Json::kObject;
      ++i_;
      if (eat('}')) return v;
      do {
        const std::string k = str();
        if (!eat(':')) fail("expected ':'");
        v.o[k] = value();
      } while (eat(','));
      if (!eat('}')) fail("expected '}'");
    } else if (c == '[') {
      v.kind = Json::kArray;
      ++i_;
      if (eat(']')) return v;
      do v.a.push_back(value());
      while (eat(','));
      if (!eat(']')) fail("expected ']'");
    } else if (c == '"') {
      v.kind = Json::kString;
      v.s = str();
    } else if (t_.compare(i_, 4, "true") == 0) {
      v.kind = Json::kBool, v.b = true, i_ += 4;
    } else if (t_.compare(i_, 5, "false") == 0) {
      v.kind = Json::kBool, i_ += 5;
    } else if (t_.compare(i_, 4, "null") == 0) {
      i_ += 4;  // a non-finite number
    } else {
      std::size_t used = 0;
      v.kind = Json::kNumber;
      v.n = std::stod(t_.substr(i_, 40), &used);
      if (used == 0) fail("expected a value");
      i_ += used;
    }
    return v;
  }
  std::string t_;
  std::size_t i_ = 0;
};

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
  const Json root = Parser(read(kDir / "claims.json")).parse();
  const Json& claims = root.at("claims");
  REQUIRE(claims.kind == Json::kArray);
  std::vector<std::string> ids;
  for (const Json& c : claims.a) {
    const std::string id = c.at("id").s;
    ids.push_back(id);
    CAPTURE(id);
    REQUIRE(c.at("holds").kind == Json::kBool);
    REQUIRE(c.at("checks").kind == Json::kArray);
    CHECK(!c.at("statement").s.empty());
    CHECK(!c.at("runs").a.empty());
    CHECK(!c.at("measured").o.empty());
    const bool evaluated = c.at("reason").s.rfind("not evaluated", 0) != 0;
    bool all = evaluated && !c.at("checks").a.empty();
    for (const Json& k : c.at("checks").a) {
      CAPTURE(k.at("quantity").s);
      CHECK(!k.at("why").s.empty());
      all = all && satisfied(k.at("value").n, k.at("op").s, k.at("threshold").n);
    }
    CHECK(c.at("holds").b == all);
  }
  CHECK(ids == std::vector<std::string>{"C1", "C2", "C3", "C4", "C5", "C6", "C4'", "C5'"});
}

TEST_CASE("the compliance claims name their damping law and its effective restitution") {
  const Json root = Parser(read(kDir / "claims.json")).parse();
  std::map<std::string, const Json*> by_id;
  for (const Json& c : root.at("claims").a) by_id[c.at("id").s] = &c;
  const std::map<std::string, std::string> laws{{"C4", "hertzdamp"},
                                                {"C5", "hertzdamp"},
                                                {"C4'", "hunt_crossley_exact"},
                                                {"C5'", "hunt_crossley_exact"}};
  for (const auto& [id, name] : laws) {
    CAPTURE(id);
    REQUIRE(by_id.count(id) == 1);
    const Json& law = by_id[id]->at("law");
    REQUIRE(law.kind == Json::kObject);
    CHECK(law.at("name").s == name);
    const double chi = law.at("chi").n, e = law.at("effective_restitution").n;
    const double eps = law.at("nonsmooth_restitution").n;
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
    for (const Json& k : by_id[id]->at("checks").a) a.push_back(k.at("quantity").s);
    for (const Json& k : by_id[std::string(id) + "'"]->at("checks").a) {
      b.push_back(k.at("quantity").s);
    }
    CHECK(a == b);
  }
  for (const auto& [id, c] : by_id) {
    if (laws.count(id) == 0) CHECK(c->at("law").kind == Json::kNull);
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
  const Json root = Parser(read(kDir / "claims.json")).parse();
  std::map<std::string, std::map<std::string, std::pair<std::string, double>>> out;
  for (const Json& c : root.at("claims").a) {
    for (const Json& k : c.at("checks").a) {
      out[c.at("id").s][k.at("quantity").s] = {k.at("op").s, k.at("threshold").n};
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
  const Json u = Parser(read(kDir / "uncertainty.json")).parse();
  const Csv samples = read_csv(kDir / "uncertainty.csv");
  const Csv oat = read_csv(kDir / "uncertainty-oat.csv");
  REQUIRE(u.at("claims").kind == Json::kArray);
  CHECK(u.at("samples").n == double(samples.rows.size()));
  CHECK(!samples.rows.empty());
  for (const Json& c : u.at("claims").a) {
    const std::string id = c.at("id").s;
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
    CHECK(c.at("samples").n == double(evaluated));
    CHECK(c.at("holds").n == double(holds));
    if (evaluated > 0) {
      const double p = double(holds) / double(evaluated);
      CHECK(c.at("share").n == doctest::Approx(p).epsilon(1e-12));
      CHECK(c.at("standard_error").n ==
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
    for (const Json& f : c.at("flips").a) {
      written.insert(f.at("assumption").s + " " + f.at("end").s);
    }
    CHECK(expected == written);
  }
  for (const char* ext : {".png", ".svg", ".csv"}) {
    const auto p = kDir / (std::string("uncertainty-tornado") + ext);
    CHECK(fs::exists(p));
    CHECK(fs::file_size(p) > 100);
  }
}
