// The figures as registered entries. A figure is one file (paper-figures/fig<n>.cpp) with one
// function that returns its entry: its name, the runs it needs, and how it draws itself from
// them; its gnuplot script is paper-figures/gnuplot/<name>.gp. Adding a figure is that file,
// its script, and one line in registered_figures() (paper-figures/figure.cpp).
//
//   Figure fig3_response() {
//     return {"fig3-response",
//             [](const Study&) { return std::vector<RunSpec>{...}; },  // runs it needs
//             nullptr,                                                   // no follow-up runs
//             [](const Study& s, const Canvas& c) { ...; return draw_csv_and_plot(...); }};
//   }
//
// make_figures (figures.cpp) makes every figure's runs through the sweep runner, then every
// figure's follow-up runs (those placed by the first runs' events), then draws each figure.
#pragma once

#include "integrators/compliance.hpp"
#include "paper-figures/claim_runs.hpp"
#include "paper-figures/plot.hpp"
#include "paper-figures/runs.hpp"
#include "scene/scene.hpp"

#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace nsb::paper_figures {

// The set of runs (docs/paper-figures.md, "What is run"): --quick or the full set.
struct Setup {
  bool quick = false;
  std::vector<int> pga_runs;        // runs of Fig. 6 and C2, C3
  std::vector<int> mu0_runs;        // runs repeated with mu = 0 (C1)
  std::vector<double> factors;      // compliance stiffness factors (Fig. 7, C4)
  std::vector<double> windows;      // stiffness factors of the first pounding (Fig. 8, C5)
  double compliance_end = 0.0;      // [s] of the compliance runs; 0: the scene's end time
  std::vector<double> eta_skews;    // [deg] of the eta map's points
  std::vector<double> eta_ratios;   // W/L of the eta map's points
};
Setup make_setup(bool quick);

// What a figure and a claim read: the set, the scenes, the runs made so far, Fig. 6's sweep.
struct Study {
  Setup setup;
  std::filesystem::path scenes;  // folder of the scene files
  RunSet runs;
  Fig6Sweep fig6;                // the nominal sweep of Fig. 6 and C1-C3
};

// Where a figure is drawn: the output folder and the gnuplot executable.
struct Canvas {
  std::filesystem::path dir;
  std::string gnuplot = "gnuplot";
};

// What a figure drew: its files (none when its runs did not allow it, e.g. Fig. 8 without a
// pounding), and what went wrong with gnuplot (empty on success).
struct Drawing {
  std::vector<std::filesystem::path> files;
  std::string error;
};

struct Figure {
  std::string name;  // stem of <name>.csv, .png, .svg, .gp; its script is gnuplot/<name>.gp
  // The runs it needs, from the set alone (Study::runs is still empty).
  std::function<std::vector<RunSpec>(const Study&)> runs;
  // Runs placed by the first runs' records (e.g. a window around the first pounding); may be
  // empty. Study::runs holds every figure's first runs.
  std::function<std::vector<RunSpec>(const Study&)> follow_up;
  // Writes <dir>/<name>.csv from the runs and draws it.
  std::function<Drawing(const Study&, const Canvas&)> draw;
};

// Every figure, in the order they are drawn.
const std::vector<Figure>& registered_figures();

// A gnuplot variable set before a figure's script: name and its value as gnuplot text.
struct GnuplotVariable {
  std::string name, value;
};
GnuplotVariable gnuplot_number(const std::string& name, double v);          // 17 digits
GnuplotVariable gnuplot_string(const std::string& name, const std::string& text);  // quoted

// The folder of the figures' gnuplot scripts: paper-figures/gnuplot of the source tree.
std::filesystem::path gnuplot_dir();

// Writes the table as <dir>/<name>.csv and draws it with the script gnuplot/<name>.gp of the
// source tree (NSB_GNUPLOT_DIR), the variables set before the script and `data` naming the
// CSV. The .gp written beside the figure is the variables followed by the script, so that it
// redraws the figure on its own.
Drawing draw_table(const Canvas& canvas, const std::string& name, const Table& table,
                   const std::vector<GnuplotVariable>& variables, PlotSize size = {});

// The name of a stiffness factor or a number in run names and labels: "0.0001", "100", "12".
std::string factor_name(double f);
// Factor names separated by spaces: a gnuplot word list, "0.0001 0.01 100".
std::string factor_list(const std::vector<double>& factors);

// Runs of excitation 5 shared by the figures and the claims.
inline constexpr const char* kExc5Moreau = "exc5-moreau";
inline constexpr const char* kExc5Event = "exc5-event";
inline constexpr const char* kExc5Sliding = "exc5-moreau-sliding";
// The damping laws of eq. (9) the compliance comparisons are made with: the paper's
// Hertz-damp (Lankarani & Nikravesh; C4, C5) and the law whose effective restitution equals
// the nonsmooth runs' eps (Hunt-Crossley exact; C4', C5'), docs/compliance.md.
inline constexpr std::array<integrators::DampingLaw, 2> kComparedLaws{
    integrators::DampingLaw::kHertzDamp, integrators::DampingLaw::kHuntCrossleyExact};
// "exc5-k<factor>" (Hertz-damp) or "exc5-k<factor>-<law>": Fig. 7, C4, C4'.
std::string exc5_compliance_run(double factor,
                                integrators::DampingLaw law = integrators::DampingLaw::kHertzDamp);
// exc5_compliance_run(factor, law) + "-first": Fig. 8, C5, C5'.
std::string exc5_window_run(double factor,
                            integrators::DampingLaw law = integrators::DampingLaw::kHertzDamp);
// The overrides of a compliance run of excitation 5 at c k under a law.
std::vector<std::string> compliance_overrides(double factor, integrators::DampingLaw law);
// A damping law at the nonsmooth runs' restitution eps of excitation 5 (the scene's
// model.seats.restitution): chi(eps) and the effective restitution of a single impact under
// it (integrators::hunt_crossley_restitution), e.g. 0.663 for Hertz-damp at eps = 0.
LawRestitution law_restitution(const Study& study, integrators::DampingLaw law);
// The scene stem of excitation n, "bridge-exc<n>".
std::string exc(int n);
// Excitation 5 under Moreau-Jean, as Figs. 3, 4, 5, 7 and 8 use it.
RunSpec exc5_moreau();

// The longest sliding contact of a run (contact 0 when none).
Sliding longest_sliding_of(const FigureRun& run);
// Coulomb's law over the longest slide of excitation 5, from the run that records its every
// step (kExc5Sliding) with the friction coefficient of its scene (Fig. 5, C6).
SlidingState sliding_state_of(const FigureRun& sliding, const Sliding& slide, double mu);
// A run's scene, loaded with the run's overrides (not integrated): its system's parameters.
scene::Scene load_run_scene(const Study& study, const RunSpec& spec);

// The claims C1..C6 from the figures' runs and Fig. 6's sweep (paper-figures/claims.hpp),
// each with the runs it used.
std::vector<Claim> nominal_claims(const Study& study);

// Fig. 8 and C5 look at excitation 5's first pounding from this long before it [s]: the gap
// still open, before the softest contact (1e-4 k) starts to close.
inline constexpr double kFirstPoundingLead = 0.02;
// Every compliance step is recorded up to this long after the first pounding, long enough for
// the softest contact (1e-4 k) to open again: measured 0.06 s.
inline constexpr double kFirstPoundingWindow = 0.15;  // [s]

}  // namespace nsb::paper_figures
