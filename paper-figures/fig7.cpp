// Fig. 7 of Shi & Dimitrakopoulos (2017): the rotation under excitation 5, nonsmooth
// (Moreau-Jean) against the compliance method at several contact stiffnesses c k.
#include "paper-figures/figure.hpp"

namespace nsb::paper_figures {

Figure fig7_compliance() {
  Figure f;
  f.name = "fig7-compliance";
  f.runs = [](const Study& s) {
    std::vector<RunSpec> v{exc5_moreau()};
    for (double k : s.setup.factors) {
      std::vector<std::string> o{"solver.method=compliance",
                                 "solver.stiffness_factor=" + factor_name(k)};
      if (s.setup.compliance_end > 0) {
        o.push_back("solver.end_time=" + factor_name(s.setup.compliance_end));
      }
      v.push_back({exc5_compliance_run(k), exc(kExampleRun), o});
    }
    return v;
  };
  f.draw = [name = f.name](const Study& s, const Canvas& canvas) {
    const RunRecord& mj = s.runs.at(kExc5Moreau);
    const double t_end = s.setup.compliance_end > 0 ? s.setup.compliance_end : mj.end_time;
    Table t{{"t", "theta_nonsmooth"}};
    std::vector<const History*> k;
    for (double c : s.setup.factors) {
      t.columns.push_back("theta_k" + factor_name(c));
      k.push_back(&s.runs.at(exc5_compliance_run(c)).history);
    }
    const auto ts = mj.history.series("t"), th = mj.history.series("theta");
    for (std::size_t i = 0; i < ts.size() && ts[i] <= t_end; ++i) {
      std::vector<double> row{ts[i], th[i]};
      for (const History* h : k) row.push_back(value_at(*h, "theta", ts[i]));
      t.add(row);
    }
    return draw_table(canvas, name, t, {gnuplot_string("factors", factor_list(s.setup.factors))},
                      {1200, 500});
  };
  return f;
}

}  // namespace nsb::paper_figures
