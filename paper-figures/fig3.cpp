// Fig. 3 of Shi & Dimitrakopoulos (2017): the deck's response and gaps under excitation 5, the
// Moreau-Jean history with the event-driven one interpolated at its samples.
#include "paper-figures/figure.hpp"

namespace nsb::paper_figures {

Figure fig3_response() {
  Figure f;
  f.name = "fig3-response";
  f.runs = [](const Study&) {
    return std::vector<RunSpec>{
        exc5_moreau(), {kExc5Event, exc(kExampleRun), {"solver.method=event_driven"}}};
  };
  f.draw = [name = f.name](const Study& s, const Canvas& canvas) {
    const History& mj = s.runs.at(kExc5Moreau).history;
    const History& ed = s.runs.at(kExc5Event).history;
    Table t{{"t", "x", "y", "theta", "gN1", "gN2", "gN3", "gN4", "x_event", "y_event",
             "theta_event"}};
    const std::size_t ct = mj.column("t");
    for (std::size_t i = 0; i < mj.rows(); ++i) {
      const double time = mj.at(i, ct);
      std::vector<double> row{time};
      for (const char* c : {"x", "y", "theta", "gN1", "gN2", "gN3", "gN4"})
        row.push_back(mj.at(i, mj.column(c)));
      for (const char* c : {"x", "y", "theta"}) row.push_back(value_at(ed, c, time));
      t.add(row);
    }
    return draw_table(canvas, name, t, {});
  };
  return f;
}

}  // namespace nsb::paper_figures
