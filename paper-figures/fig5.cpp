// Fig. 5 of Shi & Dimitrakopoulos (2017): the deck in plan at the start of the longest sliding
// contact of excitation 5, with the seat faces and the contact forces lambda_N n and
// lambda_T t, from a Moreau-Jean run that records every step up to the slide's end.
#include "paper-figures/figure.hpp"

#include "models/bridge_design.hpp"
#include "models/contact_geometry.hpp"

namespace nsb::paper_figures {

namespace {

// The history is recorded at every step from slightly before the sliding contact.
constexpr double kSlidingLead = 0.05;  // [s]
// Forces are drawn as arrows of 1 m per 200 kN.
constexpr double kForceScale = 1.0 / 200.0;  // [m/kN]

// Rows: kind 0 deck outline, 1 seat faces, 2 normal force, 3 tangential force; x, y [m] and
// the arrow components dx, dy [m] (forces at kForceScale). Returns the contact point.
Eigen::Vector2d plan_view(Table& tab, const models::BridgeDesign& b, const History& r,
                          std::size_t row, const SlidingState& st) {
  const Eigen::Vector3d q(r.at(row, r.column("x")), r.at(row, r.column("y")),
                          r.at(row, r.column("theta")));
  const Eigen::Vector3d u(r.at(row, r.column("vx")), r.at(row, r.column("vy")),
                          r.at(row, r.column("omega")));
  const double t = r.at(row, r.column("t"));
  const auto corners = b.deck.corner_faces();
  const Eigen::Rotation2Dd rot(q(2));
  for (int i : {0, 2, 3, 1, 0}) {  // corners 1, 3, 4, 2, 1: the outline
    const Eigen::Vector2d p = q.head<2>() + rot * corners[static_cast<std::size_t>(i)].body_point;
    tab.add({0, p.x(), p.y(), 0, 0});
  }
  const double half = 0.75 * b.deck.width;
  for (int a = 0; a < 2; ++a) {
    const auto m = b.seat_motion(a, t);
    const auto& cf = corners[a == 0 ? 0 : 2];
    const Eigen::Vector2d n = Eigen::Rotation2Dd(m.position(2)) * cf.face_normal;
    const Eigen::Vector2d tn = models::perp(n), o = m.position.head<2>();
    tab.add(
        {1, o.x() - half * tn.x(), o.y() - half * tn.y(), 2 * half * tn.x(), 2 * half * tn.y()});
  }
  const int c = st.slide.contact;
  const auto k = models::corner_contact(corners[static_cast<std::size_t>(c - 1)], q, u,
                                        b.seat_motion(models::DeckGeometry::abutment_of(c - 1), t));
  const Eigen::Vector2d fn = st.lambda_n * kForceScale * k.normal,
                        ft = st.lambda_t * kForceScale * k.tangent;
  tab.add({2, k.point.x(), k.point.y(), fn.x(), fn.y()});
  tab.add({3, k.point.x(), k.point.y(), ft.x(), ft.y()});
  return k.point;
}

}  // namespace

Figure fig5_sliding_contact() {
  Figure f;
  f.name = "fig5-sliding-contact";
  f.runs = [](const Study&) { return std::vector<RunSpec>{exc5_moreau()}; };
  f.follow_up = [](const Study& s) {
    const Sliding longest = longest_sliding_of(s.runs.at(kExc5Moreau));
    std::vector<RunSpec> v;
    if (longest.contact == 0) return v;
    v.push_back(
        {kExc5Sliding,
         exc(kExampleRun),
         {"solver.method=moreau", "solver.end_time=" + factor_name(longest.end + kSlidingLead),
          "output.sample_dt=0"}});
    return v;
  };
  f.draw = [name = f.name](const Study& s, const Canvas& canvas) {
    const Sliding longest = longest_sliding_of(s.runs.at(kExc5Moreau));
    if (longest.contact == 0) return Drawing{};
    const FigureRun& run = s.runs.at(kExc5Sliding);
    const scene::Scene scene = load_run_scene(s, run.spec);
    const models::BridgeDesign& b = scene.design.value();
    const SlidingState st = sliding_state_of(run, longest, b.friction);
    const History& r = run.history;
    const auto ts = r.series("t");
    std::size_t row = 0;
    while (row + 1 < ts.size() && ts[row] < st.slide.start) ++row;
    Table tab{{"kind", "x", "y", "dx", "dy"}};
    const Eigen::Vector2d p = plan_view(tab, b, r, row, st);
    return draw_table(canvas, name, tab,
                      {gnuplot_number("contact", st.slide.contact),
                       gnuplot_number("slide_start", st.slide.start),
                       gnuplot_number("slide_end", st.slide.end), gnuplot_number("t", ts[row]),
                       gnuplot_number("lambda_n", st.lambda_n),
                       gnuplot_number("lambda_t", st.lambda_t),
                       gnuplot_number("omega", r.at(row, r.column("omega"))),
                       gnuplot_number("px", p.x()), gnuplot_number("py", p.y())},
                      {1200, 900});
  };
  return f;
}

}  // namespace nsb::paper_figures
