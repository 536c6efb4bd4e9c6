// The paper's figures and claims (Shi & Dimitrakopoulos 2017), regenerated from runs of the
// benchmark bridge (scenes/bridge-exc*.toml) and of the free deck
// (scenes/rigid-deck-straight.toml). Every run goes through the sweep module's runner (an
// ordinary scene::load_scene + integrators::integrate call) and is read back from its outputs.
// Each figure (paper-figures/figure.hpp: one registered entry per figure) is written as PNG and
// SVG (gnuplot) with the CSV it was drawn from; the claims go to claims.json and claims.md
// (paper-figures/claims.hpp). What is run, the thresholds and the run times:
// docs/paper-figures.md.
#pragma once

#include "paper-figures/claims.hpp"
#include "scene/scene.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace nsb::paper_figures {

struct FigureOptions {
  std::filesystem::path out;          // output folder, created if absent; must not be a file
  bool quick = false;                 // the reduced set: fewer runs, compliance to 12 s only
  std::filesystem::path scenes;       // folder of the scenes; empty: the source tree's scenes/
  std::string gnuplot = "gnuplot";    // gnuplot executable (on PATH or a path)
  int workers = 2;                    // runs integrated in parallel, in [1, 64]
  void validate() const;              // throws std::invalid_argument naming the field
};

struct FigureResult {
  std::vector<Claim> claims;          // C1..C6, as written to claims.json
  std::vector<std::string> figures;   // stems of the figures written (.png, .svg, .csv each)
  int runs = 0;                       // integrations performed
  std::vector<std::string> failed;    // "<run>: <status> at t = <s>" for each failed run
  std::vector<std::string> plot_errors;  // figures gnuplot did not draw
  std::filesystem::path scenes;       // the folder the scenes were read from
  double wall_time = 0.0;             // [s]
  bool succeeded() const { return failed.empty() && plot_errors.empty(); }
};

// The PGA of a bridge's input as its first bent receives it [g]: transverse or longitudinal
// (0 for a scene without a bridge design or without that motion). The figures' PGA axis and
// claim C2 use it.
double input_pga(const scene::Scene& scene, bool transverse);

// Runs everything and writes the figures, claims.json and claims.md into options.out. The
// uncertainty study of the claims' verdicts (studies/uncertainty.hpp) is run after it by the
// caller, into the same folder; claims.md points to its uncertainty.md.
// Throws std::invalid_argument for bad options or a scene that does not load (before any
// file is written); failed runs and plots are reported in the result, never thrown.
FigureResult make_figures(const FigureOptions& options);

}  // namespace nsb::paper_figures
