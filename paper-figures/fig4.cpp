// Fig. 4 of Shi & Dimitrakopoulos (2017): the deck's angular velocity under excitation 5, with
// the longest sliding contact of the Moreau-Jean run shaded.
#include "paper-figures/figure.hpp"

namespace nsb::paper_figures {

Figure fig4_omega() {
  Figure f;
  f.name = "fig4-omega";
  f.runs = [](const Study&) {
    return std::vector<RunSpec>{
        exc5_moreau(), {kExc5Event, exc(kExampleRun), {"solver.method=event_driven"}}};
  };
  f.draw = [name = f.name](const Study& s, const Canvas& canvas) {
    const FigureRun& mj = s.runs.at(kExc5Moreau);
    const History& ed = s.runs.at(kExc5Event).history;
    Table t{{"t", "omega", "omega_event"}};
    const auto ts = mj.history.series("t"), om = mj.history.series("omega");
    for (std::size_t i = 0; i < ts.size(); ++i) {
      t.add({ts[i], om[i], value_at(ed, "omega", ts[i])});
    }
    const Sliding slide = longest_sliding_of(mj);
    return draw_table(canvas, name, t,
                      {gnuplot_number("contact", slide.contact),
                       gnuplot_number("slide_start", slide.start),
                       gnuplot_number("slide_end", slide.end)},
                      {1200, 500});
  };
  return f;
}

}  // namespace nsb::paper_figures
