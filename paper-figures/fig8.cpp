// Fig. 8 of Shi & Dimitrakopoulos (2017): the first pounding of excitation 5 under the
// compliance method, every step recorded in a window around it: the gap against time, and the
// force-penetration loops of the stiffer contacts, once per compared damping law of eq. (9)
// (kComparedLaws), each with its effective restitution.
#include "paper-figures/figure.hpp"

namespace nsb::paper_figures {

namespace {

// The nonsmooth run's rows of the table: law 0, the effective restitution its eps.
void add_nonsmooth_rows(Table& t, const History& mj, const std::string& g, const std::string& l,
                        double t_first, double eps) {
  const auto ts = mj.series("t"), gs = mj.series(g), ls = mj.series(l);
  for (std::size_t i = 0; i < ts.size(); ++i) {
    if (ts[i] >= t_first - kFirstPoundingLead && ts[i] <= t_first + kFirstPoundingWindow)
      t.add({0.0, 0.0, eps, ts[i], gs[i], ls[i]});
  }
}

}  // namespace

Figure fig8_first_pounding() {
  Figure f;
  f.name = "fig8-first-pounding";
  f.runs = [](const Study&) { return std::vector<RunSpec>{exc5_moreau()}; };
  f.follow_up = [](const Study& s) {
    const auto [t_first, contact] = first_impact(s.runs.at(kExc5Moreau).history);
    std::vector<RunSpec> v;
    if (contact == 0) return v;
    for (const auto law : kComparedLaws) {
      for (double k : s.setup.windows) {
        std::vector<std::string> o = compliance_overrides(k, law);
        o.push_back("solver.end_time=" + factor_name(t_first + kFirstPoundingWindow));
        o.push_back("output.sample_dt=0");
        v.push_back({exc5_window_run(k, law), exc(kExampleRun), o});
      }
    }
    return v;
  };
  f.draw = [name = f.name](const Study& s, const Canvas& canvas) {
    const History& mj = s.runs.at(kExc5Moreau).history;
    const auto [t_first, contact] = first_impact(mj);
    if (contact == 0) return Drawing{};
    const std::string g = "gN" + std::to_string(contact), l = "lambdaN" + std::to_string(contact);
    // law: 1-based position in `laws` (0: the nonsmooth run); e_eff: its effective restitution.
    Table t{{"factor", "law", "e_eff", "t", "gap", "lambda_n"}};
    std::vector<double> loops;
    std::string laws;
    double eps = 0.0;
    for (std::size_t j = 0; j < kComparedLaws.size(); ++j) {
      const LawRestitution r = law_restitution(s, kComparedLaws[j]);
      laws += (laws.empty() ? "" : " ") + r.name;
      eps = r.nonsmooth_restitution;
      for (double k : s.setup.windows) {
        const History& h = s.runs.at(exc5_window_run(k, kComparedLaws[j])).history;
        const auto ts = h.series("t"), gs = h.series(g), ls = h.series(l);
        for (std::size_t i = 0; i < ts.size(); ++i) {
          if (ts[i] >= t_first - kFirstPoundingLead)
            t.add({k, double(j + 1), r.effective_restitution, ts[i], gs[i], ls[i]});
        }
        // The loops of the stiffer contacts, as in the paper (1e0 k, 1e2 k).
        if (j == 0 && k >= 1.0) loops.push_back(k);
      }
    }
    add_nonsmooth_rows(t, mj, g, l, t_first, eps);
    return draw_table(canvas, name, t,
                      {gnuplot_number("contact", contact), gnuplot_number("t_first", t_first),
                       gnuplot_string("factors", factor_list(s.setup.windows)),
                       gnuplot_string("loop_factors", factor_list(loops)),
                       gnuplot_string("laws", laws), gnuplot_number("eps", eps)},
                      {1200, 900});
  };
  return f;
}

}  // namespace nsb::paper_figures
