// nsbridge criterion: the rotation criterion eta of eq. (1), in the form derived from the
// impact law (eqs. 3-7; docs/criterion.md), with the formula as printed for comparison.
#include "app/commands.hpp"
#include "io/csv.hpp"
#include "models/analytic.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

namespace nsb::app {
namespace {

struct CriterionArgs {
  double skew = 0.0;
  double width = 0.0;
  double length = 0.0;
  double friction = 0.0;
  bool json = false;
};

std::string number(double x) { return io::shortest(x); }

// Six significant digits for people to read.
std::string short_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

void run_criterion(const CriterionArgs& a) {
  const models::analytic::CriterionInput in{.skew_deg = a.skew, .width = a.width,
                                            .length = a.length, .friction = a.friction};
  try {
    in.validate();
  } catch (const std::invalid_argument& e) {
    // validate() names the field as the option is named (skew, width, length, friction).
    const std::string what = e.what();
    const std::string field = what.substr(0, what.find(':'));
    const double given = field == "skew"    ? a.skew
                         : field == "width" ? a.width
                         : field == "length" ? a.length
                                             : a.friction;
    throw InputError("criterion: --" + what + " (got " + number(given) + ")");
  }
  const auto c = models::analytic::rotation_criterion(in);
  // eta scales with L/W: valid inputs whose ratio overflows or underflows a double
  // (--width 1e-300 --length 1e300) make eta infinite or NaN. Such a result is no answer, and
  // it is refused rather than printed. W/L must be a normal double so that L/W is finite too.
  const double ratio = a.width / a.length;
  if (!models::analytic::finite_criterion(in, c)) {
    throw InputError("criterion: --width " + number(a.width) + " and --length " +
                     number(a.length) + " (W/L = " + number(ratio) +
                     ", mu = " + number(a.friction) +
                     ") make eta non-finite; expected W/L, L/W and mu L/W within the range of "
                     "a double");
  }
  const char* yes_no[] = {"no", "yes"};
  if (a.json) {
    std::cout << "{\"skew_deg\": " << number(a.skew) << ", \"width\": " << number(a.width)
              << ", \"length\": " << number(a.length) << ", \"friction\": " << number(a.friction)
              << ", \"eta_plus\": " << number(c.eta_plus)
              << ", \"eta_minus\": " << number(c.eta_minus)
              << ", \"rotation\": " << (c.rotation ? "true" : "false")
              << ", \"printed_eta_plus\": " << number(c.printed_eta_plus)
              << ", \"printed_eta_minus\": " << number(c.printed_eta_minus)
              << ", \"printed_rotation\": " << (c.printed_rotation ? "true" : "false") << "}\n";
    return;
  }
  std::cout << "rotation criterion eta (eq. 1, derived from the impact law, eqs. 3-7)\n"
            << "  skew " << short_number(a.skew) << " deg, W = " << short_number(a.width)
            << " m, L = " << short_number(a.length)
            << " m, W/L = " << short_number(a.width / a.length)
            << ", mu = " << short_number(a.friction) << "\n"
            << "  eta+ = sin(2a)/(2W/L) + mu cos^2(a)/(W/L) = " << short_number(c.eta_plus) << "\n"
            << "  eta- = sin(2a)/(2W/L) - mu cos^2(a)/(W/L) = " << short_number(c.eta_minus) << "\n"
            << "  rotation predicted (max |eta+-| > 1): " << yes_no[c.rotation] << "\n"
            << "  eq. (1) as printed (2 mu in place of mu): eta+ = "
            << short_number(c.printed_eta_plus)
            << ", eta- = " << short_number(c.printed_eta_minus)
            << ", rotation: " << yes_no[c.printed_rotation] << "\n";
}

}  // namespace

void add_criterion_command(CLI::App& app) {
  auto args = std::make_shared<CriterionArgs>();
  auto* cmd = app.add_subcommand(
      "criterion",
      "Rotation criterion eta of eq. (1) (derived form, docs/criterion.md): both branches and "
      "whether a deck-abutment impact is predicted to rotate the deck (|eta| > 1)");
  cmd->add_option("--skew", args->skew, "skew angle alpha [deg], in (-90, 90)")->required();
  cmd->add_option("--width", args->width, "deck width W [m], > 0")->required();
  cmd->add_option("--length", args->length, "deck length L [m], > 0")->required();
  cmd->add_option("--friction", args->friction, "Coulomb friction coefficient mu, >= 0")
      ->required();
  cmd->add_flag("--json", args->json, "print one JSON object instead of text");
  cmd->callback([args] { run_criterion(*args); });
}

}  // namespace nsb::app
