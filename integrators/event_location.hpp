// The one root finder of the event-driven integrator: every event function (a gap, a normal
// force, a slip velocity, the distance to the friction cone, a gap rate at an apex) is
// located by Brent's method (GSL's gsl_root_fsolver_brent; Brent 1973, "Algorithms for
// Minimization without Derivatives", ch. 4) on the dense output of the smooth phase.
#pragma once

#include <gsl/gsl_roots.h>

#include <memory>

namespace nsb::integrators::detail {

class EventRootFinder {
 public:
  // time_tolerance [s] > 0: absolute width of the final bracket. The solver is allocated once
  // here and reused by every location. The first finder of the process turns GSL's error
  // handler off, once (std::call_once) and for good: GSL reports a bracket that does not
  // straddle the root through it, which by default aborts; the codes it returns instead are
  // read here. No run switches the process-wide handler, so runs on threads do not race.
  explicit EventRootFinder(double time_tolerance);

  // Brent's method on fun over [a, b] with fun(a) >= 0 > fun(b). Returns the first time of the
  // final bracket past the crossing (fun < 0 there), to time_tolerance; b when b <= a.
  template <class F>
  double first_crossing(const F& fun, double a, double b) {
    if (!(b > a)) return b;
    struct Thunk {
      const F* f;
      static double call(double x, void* p) { return (*static_cast<const Thunk*>(p)->f)(x); }
    } thunk{&fun};
    gsl_function gf;
    gf.function = &Thunk::call;
    gf.params = &thunk;
    double lo = a, hi = b;
    bracket(gf, lo, hi);
    // Keep the side past the crossing (Brent's bracket always straddles the root).
    if (fun(hi) >= 0.0 && fun(lo) < 0.0) return lo;
    return hi;
  }

 private:
  // Narrows [lo, hi] around the root of f by Brent's iterations until it is time_tolerance
  // wide; leaves it as it is when GSL rejects the bracket.
  void bracket(gsl_function& f, double& lo, double& hi);

  struct FsolverFree {
    void operator()(gsl_root_fsolver* s) const { gsl_root_fsolver_free(s); }
  };
  std::unique_ptr<gsl_root_fsolver, FsolverFree> solver_;
  double tolerance_ = 0.0;
};

}  // namespace nsb::integrators::detail
