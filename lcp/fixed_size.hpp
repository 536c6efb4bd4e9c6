// Kernels of the solvers' small-problem paths, with the size known at compile time.
//
// The bridge's LCPs are tiny (eq. 6: n = 3 per contact, at most 12), and so are most problems
// of Siconos's collection. At such sizes the loop bookkeeping of a run-time size (trip counts,
// alignment peeling, calls into Eigen's dynamic kernels) costs as much as the arithmetic. Each
// solver therefore instantiates its core for n = 1, ..., kMaxFixed with N = n a compile-time
// constant (the loops unroll) and for N = Eigen::Dynamic (n read at run time). The arithmetic
// is the same in every instantiation, operation for operation, so the result does not depend
// on which one ran.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

namespace nsb::lcp::fixed {

// Sizes 1..kMaxFixed run with a compile-time n: 12 is the largest eq. (6) problem of the
// bridge (4 contacts); Siconos's small collection problems (n <= 9) fall below it too.
inline constexpr int kMaxFixed = 12;

template <int N>
using Size = std::integral_constant<int, N>;

// Calls f(Size<n>{}) for 1 <= n <= kMaxFixed, and f(Size<Eigen::Dynamic>{}) otherwise.
template <class F>
decltype(auto) dispatch(Eigen::Index n, F&& f) {
  switch (n) {
    case 1: return f(Size<1>{});
    case 2: return f(Size<2>{});
    case 3: return f(Size<3>{});
    case 4: return f(Size<4>{});
    case 5: return f(Size<5>{});
    case 6: return f(Size<6>{});
    case 7: return f(Size<7>{});
    case 8: return f(Size<8>{});
    case 9: return f(Size<9>{});
    case 10: return f(Size<10>{});
    case 11: return f(Size<11>{});
    case 12: return f(Size<12>{});
    default: return f(Size<Eigen::Dynamic>{});
  }
}

// n of an instantiation: the compile-time N, or the run-time n for Eigen::Dynamic.
template <int N>
constexpr Eigen::Index size(Eigen::Index n) {
  if constexpr (N > 0) {
    return N;
  } else {
    return n;
  }
}

// True if the n x n column-major array M (leading dimension n) and q hold only finite
// numbers: 0 x is 0 for a finite x and NaN for NaN or +-inf, so one sum decides. Eigen's sum
// keeps several partial sums, so the n^2 additions are not one dependency chain.
template <int N>
bool finite(const double* M, const double* q, Eigen::Index n_runtime) {
  const Eigen::Index n = size<N>(n_runtime);
  constexpr int kSquare = N > 0 ? N * N : Eigen::Dynamic;
  using Column = Eigen::Matrix<double, kSquare, 1>;
  using Vec = Eigen::Matrix<double, N, 1>;
  return (Eigen::Map<const Column>(M, n * n).array() * 0.0).sum() +
             (Eigen::Map<const Vec>(q, n).array() * 0.0).sum() ==
         0.0;
}

// w = M z + q, column by column (M column-major, leading dimension ld); zero z_j skip their
// column, as in lcp::residual.
template <int N>
void product(const double* M, Eigen::Index ld, const double* q, const double* z, double* w,
             Eigen::Index n_runtime) {
  const Eigen::Index n = size<N>(n_runtime);
  for (Eigen::Index i = 0; i < n; ++i) w[i] = q[i];
  for (Eigen::Index j = 0; j < n; ++j) {
    const double zj = z[j];
    if (zj == 0.0) continue;
    const double* c = M + j * ld;
    for (Eigen::Index i = 0; i < n; ++i) w[i] += c[i] * zj;
  }
}

// lcp::residual and lcp::siconos_error from (z, w = M z + q) in one pass, with the same
// conventions: a NaN entry makes both infinite; n = 0 gives 0.
template <int N>
void measures(const double* q, const double* z, const double* w, Eigen::Index n_runtime,
              double& natural, double& siconos) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const Eigen::Index n = size<N>(n_runtime);
  double worst = 0.0;
  double sum = 0.0;
  double qmax = 0.0;
  double qsum = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double v = std::abs(std::min(z[i], w[i]));
    if (!(v <= worst)) worst = std::isnan(v) ? kInf : v;
    const double d = z[i] - std::max(0.0, z[i] - w[i]);
    sum += d * d;
    qmax = std::max(qmax, std::abs(q[i]));
    qsum += q[i] * q[i];
  }
  if (n == 0) {
    natural = 0.0;
    siconos = 0.0;
    return;
  }
  natural = worst / (1.0 + qmax);
  const double qn = std::sqrt(qsum);
  const double e = std::sqrt(sum) / (qn > 0.0 ? qn : 1.0);
  siconos = std::isnan(e) ? kInf : e;
}

}  // namespace nsb::lcp::fixed
