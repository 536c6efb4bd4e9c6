// nsbridge spectrum: elastic response spectra (Sd, PSV, PSA) of ground-motion records by the
// exact piecewise-linear recurrence (models/response_spectrum.hpp; docs/spectra.md).
#include "app/commands.hpp"
#include "io/csv.hpp"
#include "io/files.hpp"
#include "io/gnuplot.hpp"
#include "io/json.hpp"
#include "models/ground_motion.hpp"
#include "models/response_spectrum.hpp"
#include "scene/records.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace nsb::app {
namespace {

namespace fs = std::filesystem;

struct SpectrumArgs {
  std::vector<std::string> records;
  double damping = 0.05;
  std::string periods = "nga";
  std::string csv;
  std::string plot;
  double unit = 1.0;
  bool json = false;
};

const char* const kPeriodsForms =
    "expected 'nga', a comma-separated list of periods [s] >= 0 (0 = PGA), or a:b:n "
    "(n >= 2 log-spaced periods from a to b, 0 < a < b)";

// A whole token as a finite double, or nothing.
bool parse_double(std::string_view s, double& x) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
  return !s.empty() && ec == std::errc() && ptr == s.data() + s.size() && std::isfinite(x);
}

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> out;
  for (std::size_t start = 0;;) {
    const std::size_t at = s.find(sep, start);
    out.push_back(s.substr(start, at == std::string_view::npos ? at : at - start));
    if (at == std::string_view::npos) return out;
    start = at + 1;
  }
}

// --periods: 'nga', 'T1,T2,...' or 'a:b:n'.
std::vector<double> parse_periods(const std::string& text) {
  const std::string where = "spectrum: --periods '" + text + "': ";
  if (text == "nga") {
    const auto p = models::nga_west2_periods();
    return {p.begin(), p.end()};
  }
  if (text.find(':') != std::string::npos) {
    const auto parts = split(text, ':');
    double a = 0.0, b = 0.0, n = 0.0;
    if (parts.size() != 3 || !parse_double(parts[0], a) || !parse_double(parts[1], b) ||
        !parse_double(parts[2], n) || n != std::floor(n) || n > 1e6) {
      throw InputError(where + kPeriodsForms);
    }
    try {
      return models::log_spaced_periods(a, b, static_cast<int>(n));
    } catch (const std::invalid_argument& e) {
      throw InputError(where + e.what());
    }
  }
  std::vector<double> out;
  for (const auto tok : split(text, ',')) {
    double t = 0.0;
    if (!parse_double(tok, t) || t < 0.0) {
      throw InputError(where + "'" + std::string(tok) + "' is not a period; " + kPeriodsForms);
    }
    out.push_back(t);
  }
  return out;
}

// The readers the scenes use (scene/records.hpp): by extension, .AT2 in g, .csv and anything
// else (two columns "t a") in file units times --unit.
models::Record read_record(const std::string& name, double unit) {
  const fs::path path(name);
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".at2") return scene::read_at2(path, models::kSpectrumGravity);
  if (ext == ".csv") return scene::read_csv(path, unit);
  return scene::read_two_column(path, unit);
}

// An output file's folder must exist, so that nothing fails after the work is done.
void check_output(const std::string& option, const std::string& file) {
  if (file.empty()) return;
  const fs::path dir = fs::path(file).parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec)) {
    throw InputError("spectrum: " + option + " " + file + ": folder " + dir.string() +
                     " does not exist");
  }
  if (fs::is_directory(file, ec)) {
    throw InputError("spectrum: " + option + " " + file + ": is a folder; expected a file name");
  }
}

// The gnuplot script of PSA against T (log axis), one curve per record, the data inline.
std::string plot_script(const std::vector<models::Spectrum>& spectra) {
  std::ostringstream gp;
  gp << "set logscale x\nset grid\nset xlabel 'period T [s]'\nset ylabel 'PSA [g]'\n"
     << "set title " << io::gnuplot_string("Pseudo-acceleration spectra, damping " +
                                  io::shortest(spectra.front().damping))
     << "\nset key top right noenhanced\n";
  for (std::size_t k = 0; k < spectra.size(); ++k) {
    gp << "$r" << k << " << EOD\n";
    for (std::size_t i = 0; i < spectra[k].periods.size(); ++i) {
      if (spectra[k].periods[i] > 0.0) {
        gp << io::shortest(spectra[k].periods[i]) << ' ' << io::shortest(spectra[k].psa_g[i])
           << '\n';
      }
    }
    gp << "EOD\n";
  }
  gp << "plot ";
  for (std::size_t k = 0; k < spectra.size(); ++k) {
    gp << (k ? ", " : "") << "$r" << k << " using 1:2 with lines lw 2 title "
       << io::gnuplot_string(fs::path(spectra[k].record).filename().string());
  }
  gp << '\n';
  return gp.str();
}

std::string csv_text(const std::vector<models::Spectrum>& spectra) {
  std::string out = "record,period,psa_g,sd_m,psv_m_s\n";
  for (const auto& s : spectra) {
    for (std::size_t i = 0; i < s.periods.size(); ++i) {
      out += io::csv_quote(s.record) + "," + io::shortest(s.periods[i]) + "," +
             io::shortest(s.psa_g[i]) + "," + io::shortest(s.sd_m[i]) + "," +
             io::shortest(s.psv_m_s[i]) + "\n";
    }
  }
  return out;
}

std::string json_array(const std::vector<double>& x) {
  std::string out = "[";
  for (std::size_t i = 0; i < x.size(); ++i) out += (i ? ", " : "") + io::json_number(x[i]);
  return out + "]";
}

void print(const std::vector<models::Spectrum>& spectra, const std::vector<models::Record>& records,
           bool json) {
  for (std::size_t k = 0; k < spectra.size(); ++k) {
    const auto& s = spectra[k];
    if (json) {
      std::cout << "{\"record\": " << io::json_string(s.record) << ", \"damping\": "
                << io::json_number(s.damping) << ", \"periods\": " << json_array(s.periods)
                << ", \"psa_g\": " << json_array(s.psa_g) << ", \"sd_m\": " << json_array(s.sd_m)
                << ", \"psv_m_s\": " << json_array(s.psv_m_s) << "}\n";
      continue;
    }
    const auto& r = records[k];
    double pga = 0.0;
    for (const double a : r.a) pga = std::max(pga, std::abs(a));
    char line[128];
    std::snprintf(line, sizeof line, "%zu samples, %.6g s, PGA %.4g g, damping %.4g", r.t.size(),
                  r.t.back() - r.t.front(), pga / models::kSpectrumGravity, s.damping);
    std::cout << (k ? "\n" : "") << "record " << s.record << " (" << line << ")\n";
    std::snprintf(line, sizeof line, "%10s %12s %12s %12s\n", "T [s]", "PSA [g]", "Sd [m]",
                  "PSV [m/s]");
    std::cout << line;
    for (std::size_t i = 0; i < s.periods.size(); ++i) {
      std::snprintf(line, sizeof line, "%10.4g %12.5g %12.5g %12.5g\n", s.periods[i], s.psa_g[i],
                    s.sd_m[i], s.psv_m_s[i]);
      std::cout << line;
    }
  }
}

void run_spectrum(const SpectrumArgs& a) {
  models::SpectrumOptions options;
  options.damping = a.damping;
  if (!(a.damping >= 0.0 && a.damping < 1.0)) {
    throw InputError("spectrum: --damping " + io::shortest(a.damping) +
                     ": expected a fraction of critical damping in [0, 1)");
  }
  if (!(a.unit > 0.0) || !std::isfinite(a.unit)) {
    throw InputError("spectrum: --unit " + io::shortest(a.unit) +
                     ": expected a finite factor > 0 [m/s^2 per file unit]");
  }
  options.periods = parse_periods(a.periods);
  if (!a.plot.empty() && io::terminal_for(a.plot).empty()) {
    throw InputError("spectrum: --plot " + a.plot +
                     ": expected a file ending in .png, .svg or .pdf");
  }
  check_output("--csv", a.csv);
  check_output("--plot", a.plot);
  std::vector<models::Record> records;
  std::vector<models::Spectrum> spectra;
  for (const auto& name : a.records) {
    try {
      records.push_back(read_record(name, a.unit));
      spectra.push_back(models::response_spectrum(records.back(), options));
    } catch (const std::invalid_argument& e) {
      throw InputError(std::string("spectrum: ") + e.what());
    }
  }
  // Files appear whole or not at all: the plot is drawn under a temporary name, renamed
  // once the CSV is written (atomically).
  if (!a.plot.empty()) {
    const fs::path tmp = fs::path(a.plot).parent_path() /
                         (".tmp" + std::to_string(::getpid()) + "-" +
                          fs::path(a.plot).filename().string());
    std::error_code ec;
    if (!io::draw_gnuplot("gnuplot", plot_script(spectra), tmp).empty()) {
      std::cerr << "nsbridge: spectrum: --plot " << a.plot << ": gnuplot failed; no file written\n";
      exit_code() = 1;
      return;
    }
    if (!a.csv.empty()) io::write_file_atomically(a.csv, csv_text(spectra));
    fs::rename(tmp, a.plot, ec);
    if (ec) {
      fs::remove(tmp, ec);
      throw std::runtime_error(a.plot + ": cannot write");
    }
  } else if (!a.csv.empty()) {
    io::write_file_atomically(a.csv, csv_text(spectra));
  }
  print(spectra, records, a.json);
}

}  // namespace

void add_spectrum_command(CLI::App& app) {
  auto args = std::make_shared<SpectrumArgs>();
  auto* cmd = app.add_subcommand(
      "spectrum",
      "Elastic response spectra of ground-motion records: Sd [m], PSV [m/s] and PSA [g] by "
      "the exact piecewise-linear recurrence (Nigam & Jennings 1969; docs/spectra.md)");
  cmd->add_option("records", args->records,
                  "record files: .AT2 (PEER, units of g), .csv (header, columns t,a) or two "
                  "columns 't a'")
      ->required();
  cmd->add_option("--damping", args->damping, "damping ratio zeta, in [0, 1) (default 0.05)");
  cmd->add_option("--periods", args->periods,
                  "periods [s]: 'nga' (the 105 NGA-West2 periods, 0.01-10 s; default), a list "
                  "'0,0.2,1' (0 = PGA) or a:b:n (n log-spaced periods from a to b)");
  cmd->add_option("--unit", args->unit,
                  "m/s^2 per file unit of .csv and two-column records (default 1; .AT2 is in g)");
  cmd->add_option("--csv", args->csv, "write record,period,psa_g,sd_m,psv_m_s rows to FILE");
  cmd->add_option("--plot", args->plot, "draw PSA against T (log axis) to FILE (.png, .svg, .pdf)");
  cmd->add_flag("--json", args->json, "print one JSON object per record instead of a table");
  cmd->callback([args] { run_spectrum(*args); });
}

}  // namespace nsb::app
