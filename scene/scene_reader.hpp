// Reading the TOML tables of a scene file with the schema's fields (config/schema.hpp): each
// value is converted to the field's kind, checked against the field's range or choices and
// stored through the field's member, and every error names the file, the value's line and
// column (or "(override)" for a value set by an override) and the key's path in the scene.
#pragma once

#include "config/schema.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace nsb::scene {

// A TOML document being read (a scene file or table, a sweep design, a fragility table) and
// the one error format of every value read from it: "<file>:<line>:<col>: <key>: <what>", or
// "<file>: <key> (override): <what>" for a key set by an override, "<file>: <key>: <what>" for
// a value without a source position (a table built in code).
struct Source {
  std::string file;
  std::filesystem::path dir;
  std::set<std::string> overridden;  // key paths set by overrides, e.g. "model.bents[0].height"
  mutable double record_step = 0.0;  // shortest sampling interval of the records read, before
                                     //   time scaling [s]; 0 when no record was read

  // Throws std::invalid_argument "<file>:<line>:<col>: <key>: <what>" at node n.
  [[noreturn]] void fail(const toml::node* n, const std::string& key,
                         const std::string& what) const;
};

// The largest magnitude of a scene number: the model's quantities are products of up to
// three values (1/2 m v^2, m g h, k x^2), so values within 1e100 keep them below the largest
// double (1.8e308); a physical value in kN, t, m, s is nowhere near it.
inline constexpr double kMaxMagnitude = 1e100;

// Why a number (or an element of a three-vector) of v is refused although it lies in its
// field's range, "" when it is not: a subnormal value (0 < |x| < 2.2e-308, the smallest
// normal double) has lost precision and its reciprocal overflows, so every quantity derived
// from it (a frequency from a mass, a rate from a step) is infinite; a value beyond
// kMaxMagnitude overflows the products it enters.
std::string implausible_number(const config::Value& v);

// x with at most 6 significant digits (%.6g), as messages print a number derived from inputs.
std::string six_digits(double x);
// A quantity derived from several keys, for messages: six_digits(x) when finite, else "beyond
// the range of a double" (an overflow) or "undefined" (NaN), never inf or nan.
std::string derived(double x);

// "a table", "a string", ...: the TOML type of n, for messages.
std::string type_name(const toml::node& n);

// The keys of a list of fields, in their order of declaration.
template <class S>
std::vector<std::string_view> keys_of(std::span<const config::Field<S>> fields) {
  std::vector<std::string_view> out;
  for (const auto& f : fields) out.push_back(f.key);
  return out;
}

// One TOML table of the scene: values read by field, and the check for unknown keys.
class Section {
 public:
  Section(const Source& c, const toml::table& t, std::string path)
      : c_(c), t_(t), path_(std::move(path)) {}

  const std::string& path() const { return path_; }
  const Source& context() const { return c_; }
  const toml::table& table() const { return t_; }
  std::string key_path(std::string_view key) const;
  bool has(std::string_view key) const { return t_.get(key) != nullptr; }

  [[noreturn]] void fail(std::string_view key, const std::string& what) const;
  [[noreturn]] void fail_table(const std::string& what) const;

  // Rejects the keys not in `known` before any value is checked, so that a typo is reported
  // as an unknown key ("unknown key; allowed here: ...") rather than as a missing one.
  void only(const std::vector<std::string_view>& known);

  // The value of key converted to kind (integers read as numbers where a number is expected);
  // nullopt when the key is absent. Fails naming the key when the TOML type does not fit.
  std::optional<config::Value> value(std::string_view key, config::Kind kind) const;

  // Reads field f into out when its key is present; fails naming the key when the value does
  // not fit the field. Returns whether the key was present.
  template <class S>
  bool read(const config::Field<S>& f, S& out) const {
    const auto v = value(f.key, f.kind);
    if (!v) return false;
    if (const std::string why = config::misfit(f, *v); !why.empty()) fail(f.key, why);
    if (const std::string why = implausible_number(*v); !why.empty()) fail(f.key, why);
    f.set(out, *v);
    return true;
  }
  template <class S>
  void read_all(std::span<const config::Field<S>> fields, S& out) const {
    for (const auto& f : fields) read(f, out);
  }

  // A sub-table or an array of tables; nullptr when absent, an error for another type.
  const toml::table* subtable(std::string_view key) const;
  const toml::array* array_of_tables(std::string_view key) const;

  // Rethrows a model's validation error "field: what" at the key `field` when it is one of
  // this table's keys (field_to_key maps a model field to its scene key), else at the table.
  [[noreturn]] void rethrow(const std::invalid_argument& e,
                            const std::map<std::string, std::string>& field_to_key = {}) const;

 private:
  const Source& c_;
  const toml::table& t_;
  std::string path_;
  std::vector<std::string_view> known_;
};

}  // namespace nsb::scene
