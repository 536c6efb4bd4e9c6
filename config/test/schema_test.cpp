#include "config/schema.hpp"

#include <doctest/doctest.h>

#include <array>

namespace c = nsb::config;

namespace {

enum class Colour { kRed, kBlue };
inline constexpr std::array<c::Name<Colour>, 2> kColourNames{
    {{"red", Colour::kRed}, {"blue", Colour::kBlue}}};

struct Inner {
  double length = 2.0;
};
struct Options {
  double step = 1e-4;
  int count = 3;
  bool flag = false;
  Colour colour = Colour::kBlue;
  Inner inner;
};

const std::array<c::Field<Options>, 5>& fields() {
  static const std::array<c::Field<Options>, 5> f{
      c::number<&Options::step>("step", "s", c::positive(), "time step"),
      c::integer<&Options::count>("count", c::closed(1, 10), "how many"),
      c::boolean<&Options::flag>("flag", "a switch"),
      c::choice<&kColourNames, &Options::colour>("colour", "a colour"),
      c::number<&Options::inner, &Inner::length>("length", "m", c::open(0, 5), "nested"),
  };
  return f;
}

std::span<const c::Field<Options>> span() { return {fields().data(), fields().size()}; }

}  // namespace

TEST_CASE("ranges describe themselves as the docs and messages print them") {
  CHECK(c::positive().describe() == "> 0");
  CHECK(c::non_negative().describe() == ">= 0");
  CHECK(c::closed(0.5, 1).describe() == "in [0.5, 1]");
  CHECK(c::open(0, 0.1).describe() == "in (0, 0.1)");
  CHECK(c::any().describe() == "any");
  CHECK(c::open(0, 1).contains(0.5));
  CHECK_FALSE(c::open(0, 1).contains(0.0));
  CHECK(c::closed(0, 1).contains(0.0));
  CHECK_FALSE(c::positive().contains(std::nan("")));
}

TEST_CASE("a field reads and writes its member, also through a path of members") {
  Options o;
  CHECK(std::get<double>(fields()[4].get(o)) == 2.0);
  fields()[4].set(o, c::Value{3.5});
  CHECK(o.inner.length == 3.5);
  CHECK(std::get<std::string>(fields()[3].get(o)) == "blue");
  fields()[3].set(o, c::Value{std::string("red")});
  CHECK(o.colour == Colour::kRed);
  fields()[1].set(o, c::Value{std::int64_t{7}});
  CHECK(o.count == 7);
}

TEST_CASE("misfit names the rule, the unit and the value") {
  CHECK(c::misfit(fields()[0], c::Value{-1.0}) == "must be > 0 [s] (got -1)");
  CHECK(c::misfit(fields()[0], c::Value{1e-3}).empty());
  CHECK(c::misfit(fields()[0], c::Value{std::numeric_limits<double>::infinity()}) ==
        "must be finite");
  CHECK(c::misfit(fields()[1], c::Value{std::int64_t{11}}) ==
        "must be an integer in [1, 10] (got 11)");
  CHECK(c::misfit(fields()[3], c::Value{std::string("green")}) ==
        "must be one of \"red\", \"blue\" (got \"green\")");
  CHECK(c::misfit(fields()[2], c::Value{1.0}) == "expected true or false");
}

TEST_CASE("validate_fields throws at the first field out of range, naming its key") {
  Options o;
  CHECK_NOTHROW(c::validate_fields<Options>(o, span(), "solver."));
  o.inner.length = 5.0;  // the range is open at 5
  CHECK_THROWS_WITH_AS(c::validate_fields<Options>(o, span(), "solver."),
                       "solver.length: must be in (0, 5) [m] (got 5)", std::invalid_argument);
  CHECK(c::find_field(span(), "count") == &fields()[1]);
  CHECK(c::find_field(span(), "nothing") == nullptr);
}
