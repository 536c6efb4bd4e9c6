// nsbridge criterion: the rotation criterion eta of eq. (1), in the form derived from the
// impact law (eqs. 3-7; docs/criterion.md), with the formula as printed for comparison; for a
// plan with unequal end angles or a curved deck (given by its options or by a scene), eta of
// each end (docs/criterion.md, "Unequal end angles and curved decks").
#include "app/commands.hpp"
#include "io/csv.hpp"
#include "models/analytic.hpp"
#include "models/criterion.hpp"
#include "scene/scene.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace nsb::app {
namespace {

struct CriterionArgs {
  double skew = 0.0;
  double width = 0.0;
  double length = 0.0;
  double friction = 0.0;
  double skew_left = 0.0;
  double skew_right = 0.0;
  double radius = 0.0;
  std::string scene;
  bool json = false;
  // The options as CLI11 parsed them: which were given.
  CLI::Option* skew_option = nullptr;
  CLI::Option* width_option = nullptr;
  CLI::Option* length_option = nullptr;
  CLI::Option* friction_option = nullptr;
  CLI::Option* skew_left_option = nullptr;
  CLI::Option* skew_right_option = nullptr;
  CLI::Option* radius_option = nullptr;
  bool given(const CLI::Option* o) const { return o != nullptr && o->count() > 0; }
  // A plan of its own: one of the per-end options or a scene.
  bool per_end() const {
    return !scene.empty() || given(skew_left_option) || given(skew_right_option) ||
           given(radius_option);
  }
};

std::string number(double x) { return io::shortest(x); }

// Six significant digits for people to read.
std::string short_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

void run_equal_skew(const CriterionArgs& a) {
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

// The option of a DeckGeometry field (DeckGeometry::validate names its fields).
std::string option_of(const std::string& field) {
  if (field == "skew_deg") return "--skew";
  if (field == "skew_left_deg") return "--skew-left";
  if (field == "skew_right_deg") return "--skew-right";
  return "--" + field;  // width, length, radius
}

// The plan of the per-end options: a straight deck with each end at its own angle (--skew
// for an end without one, 0 when absent), or a curved deck of centreline radius --radius and
// arc length --length.
models::DeckGeometry plan_of_options(const CriterionArgs& a) {
  models::DeckGeometry g{.length = a.length, .width = a.width, .skew_deg = a.skew};
  if (a.given(a.skew_left_option)) g.skew_left_deg = a.skew_left;
  if (a.given(a.skew_right_option)) g.skew_right_deg = a.skew_right;
  if (a.given(a.radius_option)) g.radius = a.radius;
  return g;
}

// The plan and friction of a scene's one deck (a bridge of one deck or a free deck): its
// abutment faces' angles or its radius, and the seats' mu unless --friction is given.
std::pair<models::DeckGeometry, double> plan_of_scene(const CriterionArgs& a) {
  const scene::Scene s = scene::load_scene(a.scene);
  if (!s.design) {
    throw InputError("criterion: --scene " + a.scene + ": [model] kind = \"" + s.kind +
                     "\" has no deck of one body (a bridge of one deck or a rigid_deck); for "
                     "a frame of a bridge in segments give its plan with --width, --length, "
                     "--skew-left, --skew-right or --radius");
  }
  return {s.design->deck, a.given(a.friction_option) ? a.friction : s.design->friction};
}

// eta of both ends of a plan (models::analytic::plan_criterion).
void run_per_end(const CriterionArgs& a) {
  if (!a.scene.empty()) {
    for (const CLI::Option* o : {a.skew_option, a.width_option, a.length_option,
                                 a.skew_left_option, a.skew_right_option, a.radius_option}) {
      if (a.given(o)) {
        throw InputError("criterion: " + o->get_name() +
                         " with --scene: the plan is the scene's (give --friction at most)");
      }
    }
  } else {
    for (const CLI::Option* o : {a.width_option, a.length_option, a.friction_option}) {
      if (!a.given(o)) throw InputError("criterion: " + o->get_name() + " is required");
    }
  }
  const auto [plan, friction] = a.scene.empty()
                                    ? std::pair{plan_of_options(a), a.friction}
                                    : plan_of_scene(a);
  models::analytic::PlanCriterion c;
  try {
    c = models::analytic::plan_criterion(plan, friction);
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    const std::string field = what.substr(0, what.find(':'));
    if (!a.scene.empty()) throw InputError("criterion: --scene " + a.scene + ": " + what);
    throw InputError("criterion: " + option_of(field) + what.substr(field.size()));
  }
  const char* ends[] = {"left", "right"};
  const char* yes_no[] = {"no", "yes"};
  if (a.json) {
    std::cout << "{\"plan\": \"" << (plan.curved() ? "curved" : "straight")
              << "\", \"width\": " << number(plan.width) << ", \"length\": "
              << number(plan.length) << ", \"radius\": " << number(plan.radius)
              << ", \"friction\": " << number(friction) << ", \"ends\": [";
    for (int i = 0; i < 2; ++i) {
      const auto& e = c.ends[static_cast<std::size_t>(i)];
      std::cout << (i == 0 ? "" : ", ") << "{\"end\": \"" << ends[i]
                << "\", \"angle_deg\": " << number(plan.end_skew_deg(i))
                << ", \"eta_plus\": " << number(e.eta_plus)
                << ", \"eta_minus\": " << number(e.eta_minus)
                << ", \"rotation\": " << (e.rotation ? "true" : "false") << "}";
    }
    std::cout << "], \"rotation\": " << (c.rotation ? "true" : "false") << "}\n";
    return;
  }
  std::cout << "rotation criterion eta of each end (docs/criterion.md, \"Unequal end angles "
               "and curved decks\")\n  ";
  if (plan.curved()) {
    std::cout << "curved deck, R = " << short_number(plan.radius)
              << " m, subtended angle " << short_number(plan.subtended_angle() * 180.0 / std::numbers::pi)
              << " deg";
  } else {
    std::cout << "straight deck";
  }
  std::cout << ", W = " << short_number(plan.width) << " m, L = " << short_number(plan.length)
            << " m, mu = " << short_number(friction) << "\n";
  for (int i = 0; i < 2; ++i) {
    const auto& e = c.ends[static_cast<std::size_t>(i)];
    std::cout << "  " << ends[i] << " end (face at " << short_number(plan.end_skew_deg(i))
              << " deg): eta+ = " << short_number(e.eta_plus)
              << ", eta- = " << short_number(e.eta_minus)
              << ", rotation predicted (max |eta+-| > 1): " << yes_no[e.rotation] << "\n";
  }
}

void run_criterion(const CriterionArgs& a) {
  if (a.per_end()) return run_per_end(a);
  for (const CLI::Option* o : {a.skew_option, a.width_option, a.length_option,
                               a.friction_option}) {
    if (!a.given(o)) {
      throw InputError("criterion: " + o->get_name() +
                       " is required (or a plan: --skew-left, --skew-right, --radius or "
                       "--scene)");
    }
  }
  run_equal_skew(a);
}

}  // namespace

void add_criterion_command(CLI::App& app) {
  auto args = std::make_shared<CriterionArgs>();
  auto* cmd = app.add_subcommand(
      "criterion",
      "Rotation criterion eta of eq. (1) (derived form, docs/criterion.md): both branches and "
      "whether a deck-abutment impact is predicted to rotate the deck (|eta| > 1); for a plan "
      "with unequal end angles or a curved deck (or a scene's), both branches at each end");
  args->skew_option = cmd->add_option(
      "--skew", args->skew, "skew angle alpha of both end faces [deg], in (-90, 90)");
  args->width_option = cmd->add_option("--width", args->width, "deck width W [m], > 0");
  args->length_option = cmd->add_option(
      "--length", args->length, "deck length L [m], > 0 (curved: the centreline's arc length)");
  args->friction_option = cmd->add_option(
      "--friction", args->friction,
      "Coulomb friction coefficient mu, >= 0 (with --scene: the seats' unless given)");
  args->skew_left_option = cmd->add_option(
      "--skew-left", args->skew_left,
      "the left end face's own angle [deg], in (-80, 80): eta of each end");
  args->skew_right_option = cmd->add_option(
      "--skew-right", args->skew_right,
      "the right end face's own angle [deg], in (-80, 80): eta of each end");
  args->radius_option = cmd->add_option(
      "--radius", args->radius,
      "centreline radius R of a curved deck with radial ends [m], > W/2: eta of each end");
  cmd->add_option("--scene", args->scene,
                  "the plan (and the seats' mu) of a scene's one deck: eta of each end");
  cmd->add_flag("--json", args->json, "print one JSON object instead of text");
  cmd->callback([args] { run_criterion(*args); });
}

}  // namespace nsb::app
