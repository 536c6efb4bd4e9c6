// Fig. 6 of Shi & Dimitrakopoulos (2017): the peak deck rotation against the transverse PGA,
// with pounding, with mu = 0 and without pounding. Its runs are the nominal sweep of
// Study::fig6 (fig6_sweep, paper-figures/claim_runs.hpp), which claims C1-C3 read too.
#include "paper-figures/figure.hpp"

namespace nsb::paper_figures {

Figure fig6_peak_rotation() {
  Figure f;
  f.name = "fig6-peak-rotation";
  f.runs = [](const Study&) { return std::vector<RunSpec>{}; };
  f.draw = [name = f.name](const Study& s, const Canvas& canvas) {
    Table t{{"run", "pga_transverse_g", "pga_longitudinal_g", "peak_theta_pounding",
             "peak_theta_mu0", "peak_theta_no_pounding", "impacts"}};
    for (const auto& p : s.fig6.peaks) {
      t.add({double(p.run), p.pga_y, p.pga_x, p.pounding, p.mu0, p.free, double(p.impacts)});
    }
    return draw_table(canvas, name, t, {}, {1000, 700});
  };
  return f;
}

}  // namespace nsb::paper_figures
