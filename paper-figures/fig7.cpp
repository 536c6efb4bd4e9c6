// Fig. 7 of Shi & Dimitrakopoulos (2017): the rotation under excitation 5, nonsmooth
// (Moreau-Jean) against the compliance method at several contact stiffnesses c k, once with the
// paper's Hertz-damp law and once with the law whose effective restitution equals the
// nonsmooth eps (kComparedLaws): each panel names its law and effective restitution.
#include "paper-figures/figure.hpp"

namespace nsb::paper_figures {

namespace {

// The gnuplot variables naming each law's panel: laws = 'hertzdamp ...', and per law
// e_eff_<law> and chi_<law>; eps = the nonsmooth runs' restitution.
std::vector<GnuplotVariable> law_variables(const Study& s) {
  std::vector<GnuplotVariable> v;
  std::string names;
  double eps = 0.0;
  for (const auto law : kComparedLaws) {
    const LawRestitution r = law_restitution(s, law);
    names += (names.empty() ? "" : " ") + r.name;
    v.push_back(gnuplot_number("e_eff_" + r.name, r.effective_restitution));
    v.push_back(gnuplot_number("chi_" + r.name, r.chi));
    eps = r.nonsmooth_restitution;
  }
  v.push_back(gnuplot_string("laws", names));
  v.push_back(gnuplot_number("eps", eps));
  return v;
}

}  // namespace

Figure fig7_compliance() {
  Figure f;
  f.name = "fig7-compliance";
  f.runs = [](const Study& s) {
    std::vector<RunSpec> v{exc5_moreau()};
    for (const auto law : kComparedLaws) {
      for (double k : s.setup.factors) {
        std::vector<std::string> o = compliance_overrides(k, law);
        if (s.setup.compliance_end > 0) {
          o.push_back("solver.end_time=" + factor_name(s.setup.compliance_end));
        }
        v.push_back({exc5_compliance_run(k, law), exc(kExampleRun), o});
      }
    }
    return v;
  };
  f.draw = [name = f.name](const Study& s, const Canvas& canvas) {
    const FigureRun& mj = s.runs.at(kExc5Moreau);
    const double t_end = s.setup.compliance_end > 0 ? s.setup.compliance_end : mj.end_time;
    // Columns theta_k<f>_<law>: the law is part of every compliance column's name.
    Table t{{"t", "theta_nonsmooth"}};
    std::vector<const History*> k;
    for (const auto law : kComparedLaws) {
      for (double c : s.setup.factors) {
        t.columns.push_back("theta_k" + factor_name(c) + "_" +
                            std::string(integrators::to_string(law)));
        k.push_back(&s.runs.at(exc5_compliance_run(c, law)).history);
      }
    }
    const auto ts = mj.history.series("t"), th = mj.history.series("theta");
    for (std::size_t i = 0; i < ts.size() && ts[i] <= t_end; ++i) {
      std::vector<double> row{ts[i], th[i]};
      for (const History* h : k) row.push_back(value_at(*h, "theta", ts[i]));
      t.add(row);
    }
    std::vector<GnuplotVariable> vars = law_variables(s);
    vars.push_back(gnuplot_string("factors", factor_list(s.setup.factors)));
    return draw_table(canvas, name, t, vars, {1200, 900});
  };
  return f;
}

}  // namespace nsb::paper_figures
