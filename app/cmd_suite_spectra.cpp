// nsbridge suite-spectra: the pseudo-acceleration spectra of a record suite, each record scaled
// to a common PSA at one period (the bridge's first natural period by default), their mean,
// and the ASCE 7-16 design spectrum (§11.4.6) they are compared with (docs/spectra.md,
// "Workflow: spectra").
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "integrators/system.hpp"
#include "io/csv.hpp"
#include "io/files.hpp"
#include "io/gnuplot.hpp"
#include "models/excitation_scaling.hpp"
#include "models/ground_motion.hpp"
#include "models/response_spectrum.hpp"
#include "scene/records.hpp"
#include "scene/scene.hpp"
#include "sweep/suites.hpp"

namespace nsb::app {
namespace {

namespace fs = std::filesystem;

struct SuiteSpectraArgs {
  std::string suite;                 // records.csv of the suite
  std::string component = "file_1";  // its column of the files to plot (the transverse ones)
  std::string scene;                 // a scene whose first natural period is the scaling period
  double period = 0.0;               // [s], > 0: the scaling period instead of the scene's
  double sa = 0.0;                   // [g], > 0: the common PSA; 0: the design spectrum's
  double sds = 1.0, sd1 = 0.6, tl = 8.0;  // ASCE 7-16 S_DS [g], S_D1 [g], T_L [s]
  double damping = 0.05;
  std::string out;
};

// Three significant digits, for the title.
std::string brief(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

// The scaling period: --period, or the first natural period of --scene.
double scaling_period(const SuiteSpectraArgs& a) {
  if ((a.period > 0) == !a.scene.empty()) {
    throw InputError("suite-spectra: give either --scene (its first natural period) or --period");
  }
  if (a.period > 0) return a.period;
  scene::Scene scene;
  try {
    scene = scene::load_scene(a.scene);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  const std::vector<double> periods = integrators::natural_periods(*scene.system);
  if (periods.empty() || !std::isfinite(periods.front())) {
    throw InputError("suite-spectra: --scene " + a.scene + ": no finite first natural period");
  }
  return periods.front();
}

// The gnuplot script: the scaled spectra in grey, their mean and the design spectrum. gnuplot
// runs in the picture's folder, where the CSV is.
std::string plot_script(const std::string& csv, std::size_t records, double period, double sa,
                        const SuiteSpectraArgs& a) {
  std::ostringstream gp;
  gp << "set datafile separator ','\nset logscale x\nset grid\nset key top right\n"
     << "set xlabel 'period T [s]'\nset ylabel 'PSA [g], damping " << io::shortest(a.damping)
     << "'\nset xrange [0.01:10]\n"
     << "set title \"" << records << " records scaled to PSA(T = " << brief(period)
     << " s) = " << brief(sa) << " g\\nASCE 7-16 design spectrum: S_{DS} = " << brief(a.sds)
     << " g, S_{D1} = " << brief(a.sd1) << " g, T_L = " << brief(a.tl)
     << " s (illustrative site)\"\n"
     << "set arrow from " << io::shortest(period) << ", graph 0 to " << io::shortest(period)
     << ", graph 1 nohead dt 2\n"
     << "plot for [k=2:" << records + 1 << "] '" << csv
     << "' using 1:k with lines lc rgb '#bbbbbb' notitle, \\\n"
     << "  '' using 1:" << records + 2 << " with lines lw 3 lc rgb '#1f4e9c' title 'mean', \\\n"
     << "  '' using 1:" << records + 3
     << " with lines lw 3 dt 1 lc rgb '#c0392b' title 'ASCE 7-16 design spectrum'\n";
  return gp.str();
}

void run_suite_spectra(const SuiteSpectraArgs& a) {
  const double period = scaling_period(a);
  std::vector<sweep::SuiteRecord> suite;
  try {
    suite = sweep::read_suite(a.suite, {a.component});
    (void)models::asce7_design_spectrum(a.sds, a.sd1, a.tl, period);  // checks S_DS, S_D1, T_L
  } catch (const std::invalid_argument& e) {
    throw InputError("suite-spectra: " + std::string(e.what()));
  }
  const double sa = a.sa > 0 ? a.sa : models::asce7_design_spectrum(a.sds, a.sd1, a.tl, period);
  models::SpectrumOptions options;
  options.damping = a.damping;
  std::vector<models::Spectrum> spectra;
  for (const auto& r : suite) {
    const models::Record record = scene::read_at2(r.files.front(), models::kSpectrumGravity);
    models::Spectrum s = models::response_spectrum(record, options);
    const double factor = sa / models::spectral_acceleration_g(record, period, a.damping);
    for (double& v : s.psa_g) v *= factor;
    spectra.push_back(std::move(s));
  }
  std::string csv = "period";
  for (const auto& r : suite) csv.append(",").append(io::csv_quote(r.name));
  csv += ",mean,asce7\n";
  for (std::size_t i = 0; i < options.periods.size(); ++i) {
    double mean = 0.0;
    csv += io::shortest(options.periods[i]);
    for (const auto& s : spectra) {
      csv.append(",").append(io::shortest(s.psa_g[i]));
      mean += s.psa_g[i] / static_cast<double>(spectra.size());
    }
    csv.append(",").append(io::shortest(mean)).append(",");
    csv.append(io::shortest(models::asce7_design_spectrum(a.sds, a.sd1, a.tl, options.periods[i])));
    csv.append("\n");
  }
  const fs::path dir(a.out);
  fs::create_directories(dir);
  io::write_file_atomically(dir / "suite-spectra.csv", csv);
  const std::string failed =
      io::draw_gnuplot("gnuplot", plot_script("suite-spectra.csv", suite.size(), period, sa, a),
                       dir / "suite-spectra.png");
  if (!failed.empty()) {
    std::cerr << "nsbridge: suite-spectra: " << failed << "\n";
    exit_code() = 1;
    return;
  }
  std::cout << suite.size() << " records scaled to PSA(" << io::shortest(period)
            << " s) = " << io::shortest(sa) << " g: " << (dir / "suite-spectra.csv").string()
            << ", " << (dir / "suite-spectra.png").string() << "\n";
}

}  // namespace

void add_suite_spectra_command(CLI::App& app) {
  auto args = std::make_shared<SuiteSpectraArgs>();
  auto* cmd = app.add_subcommand(
      "suite-spectra",
      "PSA spectra of a record suite scaled to a common PSA at one period, their mean and the "
      "ASCE 7-16 design spectrum (docs/spectra.md)");
  cmd->add_option("suite", args->suite,
                  "suite CSV (e.g. data/ground-motions/asce7-suite/records.csv)")
      ->required();
  cmd->add_option("--component", args->component, "the suite's column of record files (file_1)");
  cmd->add_option("--scene", args->scene, "scale at the first natural period of this scene");
  cmd->add_option("--period", args->period, "scale at this period [s] instead");
  cmd->add_option("--sa", args->sa, "the common PSA [g] (default: the design spectrum's there)");
  cmd->add_option("--sds", args->sds, "ASCE 7-16 S_DS [g] (default 1.0, illustrative)");
  cmd->add_option("--sd1", args->sd1, "ASCE 7-16 S_D1 [g] (default 0.6, illustrative)");
  cmd->add_option("--tl", args->tl, "ASCE 7-16 T_L [s] (default 8)");
  cmd->add_option("--damping", args->damping, "damping ratio zeta, in [0, 1) (default 0.05)");
  cmd->add_option("--out", args->out, "folder of suite-spectra.csv and suite-spectra.png")
      ->required();
  cmd->callback([args] { run_suite_spectra(*args); });
}

}  // namespace nsb::app
