// Checks the output of `nsbridge figures --quick` (CTest fixture figures_quick): every figure
// has its PNG, SVG and CSV and axis labels with units, and every verdict in claims.json follows
// from the numbers printed beside it. It does not check that a claim is true: it re-derives
// "holds" from the checks (value op threshold, all of them) with its own reading of the file
// and its own comparison, so that a verdict that contradicts its numbers fails here.
#include <doctest/doctest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
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
  CHECK(ids == std::vector<std::string>{"C1", "C2", "C3", "C4", "C5", "C6"});
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
