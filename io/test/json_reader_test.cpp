// Tests of the JSON reader (RFC 8259): nested objects and arrays, numbers with exponents,
// strings with every escape, and the position named by each error. Expected values are read
// off the literal texts.
#include "io/json_reader.hpp"
#include "io/json.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

namespace nsb::io {

using Type = JsonValue::Type;

TEST_CASE("nested objects and arrays keep their members in order") {
  const JsonValue v = parse_json(
      R"( {"scene": "bridge", "peaks": {"theta": {"abs_max": 3.5e-4, "t": 9.41}},
           "list": [1, [2, 3], {"k": null}, true, false], "empty": {}, "none": []} )");
  REQUIRE(v.type == Type::kObject);
  CHECK(v.keys == std::vector<std::string>{"scene", "peaks", "list", "empty", "none"});
  CHECK(v.string_member("scene") == "bridge");
  CHECK(v.string_member("peaks").empty());  // not a string
  const JsonValue& theta = v.at("peaks").at("theta");
  REQUIRE(theta.type == Type::kObject);
  CHECK(theta.at("abs_max").number == 3.5e-4);
  CHECK(theta.at("t").number == 9.41);
  const JsonValue& list = v.at("list");
  REQUIRE(list.type == Type::kArray);
  REQUIRE(list.items.size() == 5);
  CHECK(list.items[0].number == 1.0);
  REQUIRE(list.items[1].items.size() == 2);
  CHECK(list.items[1].items[1].number == 3.0);
  CHECK(list.items[2].at("k").type == Type::kNull);
  CHECK(std::isnan(list.items[2].at("k").number));  // null: a non-finite number
  CHECK((list.items[3].type == Type::kBool && list.items[3].boolean));
  CHECK((list.items[4].type == Type::kBool && !list.items[4].boolean));
  CHECK((v.at("empty").type == Type::kObject && v.at("empty").keys.empty()));
  CHECK((v.at("none").type == Type::kArray && v.at("none").items.empty()));
  // A missing member is a null value; find says it is missing.
  CHECK(v.at("absent").type == Type::kNull);
  CHECK(v.find("absent") == nullptr);
  CHECK(list.find("k") == nullptr);  // an array has no members
}

TEST_CASE("numbers: signs, fractions and exponents") {
  CHECK(parse_json("0").number == 0.0);
  CHECK(parse_json("-12").number == -12.0);
  CHECK(parse_json("1.25").number == 1.25);
  CHECK(parse_json("1e-05").number == 1e-5);
  CHECK(parse_json("-2.5E+3").number == -2500.0);
  CHECK(parse_json("6.02e23").number == 6.02e23);
  // What the writer writes reads back to the same double (shortest round trip).
  CHECK(parse_json(json_number(0.1 + 0.2)).number == 0.1 + 0.2);
  CHECK(parse_json(json_number(4.9e-324)).number == 4.9e-324);
}

TEST_CASE("strings: every escape of RFC 8259, section 7") {
  CHECK(parse_json(R"("a\"b\\c\/d")").text == "a\"b\\c/d");
  CHECK(parse_json(R"("\b\f\n\r\t")").text == "\b\f\n\r\t");
  CHECK(parse_json(R"("\u0041\u00e9\u20AC")").text == "A\xC3\xA9\xE2\x82\xAC");  // A, é, €
  CHECK(parse_json(R"("\u001f")").text == std::string(1, '\x1f'));
  // The writer's escapes read back to the text written.
  const std::string text = "quote \" backslash \\ tab \t bell \x07 é";
  CHECK(parse_json(json_string(text)).text == text);
}

// The error of text: its reason and 0-based byte position.
std::pair<std::string, std::size_t> error_of(const std::string& text) {
  try {
    parse_json(text);
  } catch (const JsonError& e) {
    CHECK(std::string(e.what()) == e.reason() + " at byte " + std::to_string(e.position() + 1));
    return {e.reason(), e.position()};
  }
  return {"no error", 0};
}

TEST_CASE("bad input: a clear reason and the byte where reading stopped") {
  using P = std::pair<std::string, std::size_t>;
  CHECK(error_of("") == P{"unexpected end", 0});
  CHECK(error_of("{\"a\": 1,}") == P{"expected a string", 8});
  CHECK(error_of("{\"a\" 1}") == P{"expected ':'", 5});
  CHECK(error_of("[1, 2") == P{"expected ']'", 5});
  CHECK(error_of("{\"a\": 1") == P{"expected '}'", 7});
  CHECK(error_of("\"abc") == P{"unterminated string", 4});
  CHECK(error_of(R"("\x")") == P{"bad escape", 3});
  CHECK(error_of(R"("\u12G4")") == P{"bad \\u escape", 6});
  CHECK(error_of("1.2.3") == P{"bad number '1.2.3'", 5});
  CHECK(error_of("nul") == P{"expected a value", 0});
  CHECK(error_of("{} x") == P{"text after the JSON value", 3});
  CHECK(error_of(std::string(70, '[') + std::string(70, ']')) == P{"nested too deep", 65});
}

}  // namespace nsb::io
