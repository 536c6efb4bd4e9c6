// The configuration schema: every options and parameters struct declares each of its fields
// once, as a Field (scene key, member, unit, range, meaning; the default is the member's
// initializer). From that one declaration
//   - validate() checks every field's range and names the key when it fails,
//   - the scene reader (scene/scene_reader.hpp) reads and checks every key with its file, line
//     and column,
//   - the tables of docs/scenes.md are generated (scene/scene_docs.hpp),
// so a key, its unit and its range are written in exactly one place.
//
//   struct MoreauJeanOptions {
//     double step = 1e-4;
//     static std::span<const config::Field<MoreauJeanOptions>> fields();
//   };
//   ... fields() {
//     static const config::Field<MoreauJeanOptions> f[] = {
//         config::number<&MoreauJeanOptions::step>("step", "s", config::positive(), "time step h"),
//     };
//     return f;
//   }
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace nsb::config {

// The values a field can hold, as the scene reader and the docs see them. Choices (enums) are
// their names; three-vectors are std::vector<double> of size 3, lists of numbers of any size.
using Value = std::variant<double, std::int64_t, bool, std::string, std::vector<double>>;

enum class Kind {
  kNumber,   // a finite double within `range`
  kInteger,  // an integer within `range`
  kBoolean,  // true or false
  kChoice,   // one of `choices` (an enum, or a string restricted to a list)
  kText,     // free text (a record file name, a description)
  kVector3,  // three finite numbers (x, y, theta)
  kNumbers,  // a list of finite numbers, each within `range` (empty: the key's default)
};

// The interval a number must lie in: [lo, hi], either end open or infinite.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;
  bool contains(double v) const;
  // "> 0", ">= 0", "in [0.5, 1]", "in (0, 0.1)", "<= 3", "any"
  std::string describe() const;
};
Range any();
Range positive();      // (0, inf)
Range non_negative();  // [0, inf)
Range closed(double lo, double hi);             // [lo, hi]
Range open(double lo, double hi);               // (lo, hi)
Range closed_open(double lo, double hi);        // [lo, hi)
Range open_closed(double lo, double hi);        // (lo, hi]

// One field of struct S.
template <class S>
struct Field {
  std::string_view key;      // the scene key within its table, e.g. "step"
  Kind kind = Kind::kNumber;
  std::string_view unit;     // "s", "m", "kN/m^1.5", "-" for a pure number, "" for non-numbers
  Range range;               // numbers and integers
  std::vector<std::string_view> choices;  // kChoice: the allowed names
  std::string_view meaning;  // one line: what it is, and what a special value (0) selects
  Value (*get)(const S&) = nullptr;      // the field's value in s
  void (*set)(S&, const Value&) = nullptr;  // stores a value already checked by check()
};

// A name and the enum value it stands for, for choice fields.
template <class E>
struct Name {
  std::string_view name;
  E value;
};

// The name of an enum value in a names list ("unknown" when absent), and the value of a name.
template <class E, std::size_t N>
std::string_view name_of(const std::array<Name<E>, N>& names, E value) {
  for (const auto& n : names) {
    if (n.value == value) return n.name;
  }
  return "unknown";
}
template <class E, std::size_t N>
std::optional<E> value_of(const std::array<Name<E>, N>& names, std::string_view name) {
  for (const auto& n : names) {
    if (n.name == name) return n.value;
  }
  return std::nullopt;
}

namespace detail {

// Follows a path of member pointers: s.*m1.*m2 ...
template <auto First, auto... Rest, class S>
constexpr auto& follow(S& s) {
  if constexpr (sizeof...(Rest) == 0) {
    return s.*First;
  } else {
    return follow<Rest...>(s.*First);
  }
}

template <class M>
struct ClassOf;
template <class C, class T>
struct ClassOf<T C::*> {
  using type = C;
};
template <auto... Path>
struct OwnerOf;
template <auto First, auto... Rest>
struct OwnerOf<First, Rest...> {
  using type = typename ClassOf<decltype(First)>::type;
};
template <auto... Path>
using Owner = typename OwnerOf<Path...>::type;

}  // namespace detail

// A double member (or a path of members to one: number<&P::deck, &Deck::length>).
template <auto... Path>
Field<detail::Owner<Path...>> number(std::string_view key, std::string_view unit, Range range,
                                     std::string_view meaning) {
  using S = detail::Owner<Path...>;
  Field<S> f;
  f.key = key;
  f.kind = Kind::kNumber;
  f.unit = unit;
  f.range = range;
  f.meaning = meaning;
  f.get = [](const S& s) -> Value {
    return static_cast<double>(detail::follow<Path...>(const_cast<S&>(s)));
  };
  f.set = [](S& s, const Value& v) {
    using T = std::remove_reference_t<decltype(detail::follow<Path...>(s))>;
    detail::follow<Path...>(s) = static_cast<T>(std::get<double>(v));
  };
  return f;
}

// An integer member (int, long, ...).
template <auto... Path>
Field<detail::Owner<Path...>> integer(std::string_view key, Range range, std::string_view meaning) {
  using S = detail::Owner<Path...>;
  Field<S> f;
  f.key = key;
  f.kind = Kind::kInteger;
  f.unit = "-";
  f.range = range;
  f.meaning = meaning;
  f.get = [](const S& s) -> Value {
    return static_cast<std::int64_t>(detail::follow<Path...>(const_cast<S&>(s)));
  };
  f.set = [](S& s, const Value& v) {
    using T = std::remove_reference_t<decltype(detail::follow<Path...>(s))>;
    detail::follow<Path...>(s) = static_cast<T>(std::get<std::int64_t>(v));
  };
  return f;
}

// A bool member.
template <auto... Path>
Field<detail::Owner<Path...>> boolean(std::string_view key, std::string_view meaning) {
  using S = detail::Owner<Path...>;
  Field<S> f;
  f.key = key;
  f.kind = Kind::kBoolean;
  f.meaning = meaning;
  f.get = [](const S& s) -> Value { return detail::follow<Path...>(const_cast<S&>(s)); };
  f.set = [](S& s, const Value& v) { detail::follow<Path...>(s) = std::get<bool>(v); };
  return f;
}

// A std::string member holding free text.
template <auto... Path>
Field<detail::Owner<Path...>> text(std::string_view key, std::string_view meaning) {
  using S = detail::Owner<Path...>;
  Field<S> f;
  f.key = key;
  f.kind = Kind::kText;
  f.meaning = meaning;
  f.get = [](const S& s) -> Value { return detail::follow<Path...>(const_cast<S&>(s)); };
  f.set = [](S& s, const Value& v) { detail::follow<Path...>(s) = std::get<std::string>(v); };
  return f;
}

// An Eigen::Vector3d (or any type with operator() and size 3) member.
template <auto... Path>
Field<detail::Owner<Path...>> vector3(std::string_view key, std::string_view unit,
                                      std::string_view meaning) {
  using S = detail::Owner<Path...>;
  Field<S> f;
  f.key = key;
  f.kind = Kind::kVector3;
  f.unit = unit;
  f.meaning = meaning;
  f.get = [](const S& s) -> Value {
    const auto& m = detail::follow<Path...>(const_cast<S&>(s));
    return std::vector<double>{m(0), m(1), m(2)};
  };
  f.set = [](S& s, const Value& v) {
    auto& m = detail::follow<Path...>(s);
    const auto& x = std::get<std::vector<double>>(v);
    for (int i = 0; i < 3; ++i) m(i) = x[static_cast<std::size_t>(i)];
  };
  return f;
}

// A std::vector<double> member: a list of numbers of any length, each within range.
template <auto... Path>
Field<detail::Owner<Path...>> numbers(std::string_view key, std::string_view unit, Range range,
                                      std::string_view meaning) {
  using S = detail::Owner<Path...>;
  Field<S> f;
  f.key = key;
  f.kind = Kind::kNumbers;
  f.unit = unit;
  f.range = range;
  f.meaning = meaning;
  f.get = [](const S& s) -> Value {
    return std::vector<double>(detail::follow<Path...>(const_cast<S&>(s)));
  };
  f.set = [](S& s, const Value& v) {
    detail::follow<Path...>(s) = std::get<std::vector<double>>(v);
  };
  return f;
}

// An enum member chosen by name; Names is a static array of Name<E> (the one list of names).
template <auto Names, auto... Path>
Field<detail::Owner<Path...>> choice(std::string_view key, std::string_view meaning) {
  using S = detail::Owner<Path...>;
  Field<S> f;
  f.key = key;
  f.kind = Kind::kChoice;
  f.meaning = meaning;
  for (const auto& n : *Names) f.choices.push_back(n.name);
  f.get = [](const S& s) -> Value {
    const auto v = detail::follow<Path...>(const_cast<S&>(s));
    for (const auto& n : *Names) {
      if (n.value == v) return std::string(n.name);
    }
    return std::string("?");
  };
  f.set = [](S& s, const Value& v) {
    const auto& name = std::get<std::string>(v);
    for (const auto& n : *Names) {
      if (n.name == name) detail::follow<Path...>(s) = n.value;
    }
  };
  return f;
}

// Why value v does not fit field f ("must be > 0 [s] (got -1)"), or "" when it fits. Checks
// the kind, finiteness, the range and the choices.
template <class S>
std::string misfit(const Field<S>& f, const Value& v);

// "must be > 0 [s]": the rule of a field, for messages and docs.
template <class S>
std::string rule(const Field<S>& f);

// A value as the docs and messages print it: 1e-08, 0.5, true, "lemke", [0, 0, 0].
std::string format_value(const Value& v);

// Checks every field of s; throws std::invalid_argument "<prefix><key>: <misfit>" for the
// first that does not fit. prefix is e.g. "solver." (empty for none).
template <class S>
void validate_fields(const S& s, std::span<const Field<S>> fields, std::string_view prefix = {}) {
  for (const auto& f : fields) {
    const std::string why = misfit(f, f.get(s));
    if (!why.empty()) {
      throw std::invalid_argument(std::string(prefix) + std::string(f.key) + ": " + why);
    }
  }
}

// The field of a key, or nullptr.
template <class S>
const Field<S>* find_field(std::span<const Field<S>> fields, std::string_view key) {
  for (const auto& f : fields) {
    if (f.key == key) return &f;
  }
  return nullptr;
}

// --- implementation of the templates -------------------------------------------------------

std::string describe_kind(Kind kind, std::string_view unit, const Range& range,
                          const std::vector<std::string_view>& choices);
std::string misfit_value(Kind kind, std::string_view unit, const Range& range,
                         const std::vector<std::string_view>& choices, const Value& v);

template <class S>
std::string rule(const Field<S>& f) {
  return describe_kind(f.kind, f.unit, f.range, f.choices);
}

template <class S>
std::string misfit(const Field<S>& f, const Value& v) {
  return misfit_value(f.kind, f.unit, f.range, f.choices, v);
}

}  // namespace nsb::config
