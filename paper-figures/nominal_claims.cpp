// The claims C1..C6 of the nominal figures: the numbers of paper-figures/claims.hpp measured
// on the figures' runs, and the runs each claim used ("not evaluated" when one failed).
#include "paper-figures/figure.hpp"


namespace nsb::paper_figures {

namespace {

// Records the runs a claim used; a run that did not complete makes it "not evaluated".
void use_runs(Claim& c, const Study& s, const std::vector<std::string>& names) {
  for (const auto& n : names) {
    c.runs.push_back(n);
    const FigureRun* r = s.runs.find(n);
    if (r == nullptr) {
      c.failure += (c.failure.empty() ? "" : "; ") + n + ": not run";
    } else if (!r->ok()) {
      c.failure += (c.failure.empty() ? "" : "; ") + r->status_text();
    }
  }
}

// The same for runs of Fig. 6's sweep, named "fig6-sweep/<run>".
void use_sweep_runs(Claim& c, const Fig6Sweep& f6, const std::vector<std::string>& names) {
  for (const auto& n : names) {
    c.runs.push_back("fig6-sweep/" + n);
    const auto it = f6.status.find(n);
    const std::string st = it == f6.status.end() ? "not run" : it->second;
    const auto status = integrators::parse_run_status(st);
    if (!status || !integrators::succeeded(*status)) {
      c.failure += (c.failure.empty() ? "" : "; ") + n + ": " + st;
    }
  }
}

// C1, C2, C3 from Fig. 6's sweep.
void claims_of_fig6(std::vector<Claim>& claims, const Study& s) {
  std::vector<std::string> mu_runs, with_pounding, pga_runs;
  for (const auto& r : fig6_runs(s.setup.pga_runs, s.setup.mu0_runs)) {
    if (r.mu0) {
      mu_runs.push_back("exc" + std::to_string(r.excitation));
      mu_runs.push_back(r.name);
      continue;
    }
    pga_runs.push_back(r.name);
    if (r.pounding) with_pounding.push_back(r.name);
  }
  claims.push_back(claim_c1(s.fig6.peaks));
  use_sweep_runs(claims.back(), s.fig6, mu_runs);
  claims.push_back(claim_c2(s.fig6.peaks));
  use_sweep_runs(claims.back(), s.fig6, with_pounding);
  claims.push_back(claim_c3(s.fig6.peaks));
  use_sweep_runs(claims.back(), s.fig6, pga_runs);
}

// C4 and C5 are judged under each compared damping law: the paper's Hertz-damp keeps the ids
// C4, C5; the law whose effective restitution equals the nonsmooth eps is C4', C5'.
void label_law(Claim& c, const Study& s, integrators::DampingLaw law) {
  if (law != integrators::DampingLaw::kHertzDamp) c.id += "'";
  c.law = law_restitution(s, law);
}

Claim c4_of(const Study& s, integrators::DampingLaw law) {
  const FigureRun& mj = s.runs.at(kExc5Moreau);
  const double t_end = s.setup.compliance_end > 0 ? s.setup.compliance_end : mj.end_time;
  std::vector<CompliancePeak> k;
  std::vector<std::string> names{kExc5Moreau};
  for (double f : s.setup.factors) {
    const History& h = s.runs.at(exc5_compliance_run(f, law)).history;
    k.push_back({f, peak(h, "theta", t_end),
                 normalized_rms_difference(mj.history, h, "theta", t_end)});
    names.push_back(exc5_compliance_run(f, law));
  }
  Claim c = claim_c4(peak(mj.history, "theta", t_end), t_end, k);
  use_runs(c, s, names);
  label_law(c, s, law);
  return c;
}

Claim c5_of(const Study& s, integrators::DampingLaw law) {
  const auto [t_first, contact] = first_impact(s.runs.at(kExc5Moreau).history);
  std::vector<FirstPounding> fps;
  std::vector<std::string> names{kExc5Moreau};
  if (contact > 0) {
    const std::string g = "gN" + std::to_string(contact);
    for (double f : s.setup.windows) {
      const History& h = s.runs.at(exc5_window_run(f, law)).history;
      fps.push_back(measure_first_pounding(f, h.series("t"), h.series(g),
                                           t_first - kFirstPoundingLead));
      names.push_back(exc5_window_run(f, law));
    }
  }
  Claim c = claim_c5(fps);
  use_runs(c, s, names);
  if (contact == 0) c.failure = "excitation 5 has no pounding";
  label_law(c, s, law);
  return c;
}

Claim c6_of(const Study& s) {
  const Sliding longest = longest_sliding_of(s.runs.at(kExc5Moreau));
  if (longest.contact == 0) {
    Claim c{"C6", "a sliding contact carries lambda_T = mu lambda_N"};
    c.failure = "excitation 5 has no sliding contact";
    return c;
  }
  const FigureRun& sr = s.runs.at(kExc5Sliding);
  const scene::Scene scene = load_run_scene(s, s.runs.at(kExc5Moreau).spec);
  const double mu = scene.design.value().friction;
  Claim c = claim_c6(sliding_state_of(sr, longest, mu), mu);
  use_runs(c, s, {kExc5Sliding});
  return c;
}

}  // namespace

std::vector<Claim> nominal_claims(const Study& s) {
  std::vector<Claim> claims;
  claims_of_fig6(claims, s);
  using integrators::DampingLaw;
  claims.push_back(c4_of(s, DampingLaw::kHertzDamp));
  claims.push_back(c5_of(s, DampingLaw::kHertzDamp));
  claims.push_back(c6_of(s));
  // C4', C5' after C6, so that the positions of C1 ... C6 stay as they were.
  claims.push_back(c4_of(s, DampingLaw::kHuntCrossleyExact));
  claims.push_back(c5_of(s, DampingLaw::kHuntCrossleyExact));
  return claims;
}

}  // namespace nsb::paper_figures
