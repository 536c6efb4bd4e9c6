// The runs step of the uncertainty study: the claims judged at one point from its runs' rows
// and outputs.
#include "studies/uncertainty_steps.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sweep/csv.hpp"

namespace nsb::studies::uncertainty {

using namespace paper_figures;  // the claims and the claim runs the study judges

namespace {

double number_or_nan(const std::string& s) {
  if (s.empty()) return std::numeric_limits<double>::quiet_NaN();
  try {
    return std::stod(s);
  } catch (const std::exception&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace

namespace {

// C6 from a run's outputs: its events and its recorded history of the sliding contact.
SlidingState sliding_state(const RunRow& r, double mu, std::string& failure) {
  const sweep::Table ev = sweep::read_csv(r.dir / "events.csv");
  const std::size_t ct = ev.column("t"), cc = ev.column("contact"), ck = ev.column("kind");
  std::vector<integrators::Event> events;
  for (const auto& f : ev.rows) {
    integrators::Event e;
    e.t = std::stod(f[ct]);
    e.contact = std::stoi(f[cc]);
    const auto kind = integrators::parse_event_kind(f[ck]);
    if (!kind) continue;
    e.kind = *kind;
    events.push_back(e);
  }
  std::vector<Sliding> slides = sliding_contacts(events, r.end_time);
  if (slides.empty()) {
    failure = "excitation 5 has no sliding contact";
    return SlidingState{};
  }
  const sweep::Table h = sweep::read_csv(r.dir / "history.csv");
  const std::size_t c_t = h.column("t");
  std::vector<double> t;
  for (const auto& f : h.rows) t.push_back(number_or_nan(f[c_t]));
  auto series = [&](const std::string& name) {
    const std::size_t c = h.column(name);
    std::vector<double> v;
    for (const auto& f : h.rows) v.push_back(number_or_nan(f[c]));
    return v;
  };
  // The history is recorded every sample_dt (5 ms), not every step: the longest slide that
  // holds a recorded sample is judged (the nominal C6 records every step of the longest).
  std::stable_sort(slides.begin(), slides.end(), [](const Sliding& a, const Sliding& b) {
    return a.end - a.start > b.end - b.start;
  });
  for (const auto& s : slides) {
    const std::string c = std::to_string(s.contact);
    SlidingState st = measure_sliding(s, mu, t, series("lambdaN" + c), series("lambdaT" + c));
    if (st.samples > 0) return st;
  }
  failure = "no recorded sample lies in a sliding contact of excitation 5";
  return SlidingState{};
}

}  // namespace

std::vector<Claim> judge(const std::map<std::string, RunRow>& runs, double mu,
                         const InputPga& pga) {
  auto get = [&](const std::string& name) -> const RunRow* {
    const auto it = runs.find(name);
    return it == runs.end() ? nullptr : &it->second;
  };
  const std::vector<Peaks> peaks = peaks_of(runs, kStudyPgaRuns, pga);
  std::vector<Claim> claims;
  for (const auto& id : kStudyClaims) {
    if (id.starts_with("C4") || id.starts_with("C5")) {
      claims.push_back(judge_compliance(id, runs));
      continue;
    }
    Claim c;
    if (id == "C1") c = claim_c1(peaks);
    if (id == "C2") c = claim_c2(peaks);
    if (id == "C3") c = claim_c3(peaks);
    bool all_ok = true;
    for (const auto& name : kClaimRuns.at(id)) {
      const RunRow* r = get(name);
      c.runs.push_back(name);
      if (r == nullptr || !r->ok()) {
        all_ok = false;
        c.failure += (c.failure.empty() ? "" : "; ") + name + ": " +
                     (r == nullptr ? std::string("not run") : r->status);
      }
    }
    if (id == "C6") {
      std::string failure = c.failure;
      const std::vector<std::string> used = c.runs;
      c = claim_c6(all_ok ? sliding_state(*get("exc5"), mu, failure) : SlidingState{}, mu);
      c.failure = failure;
      c.runs = used;
    }
    claims.push_back(std::move(c));
  }
  return claims;
}

double tornado_peak(const Rows& rows, const std::string& point) {
  const auto p = rows.find(point);
  if (p == rows.end()) return std::nan("");
  const auto r = p->second.find(kTornadoRun);
  return r == p->second.end() || !r->second.ok() ? std::nan("") : r->second.peak_theta;
}

}  // namespace nsb::studies::uncertainty
