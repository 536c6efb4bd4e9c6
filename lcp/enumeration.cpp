#include "lcp/enumeration.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace nsb::lcp {

void EnumerationOptions::validate() const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw std::invalid_argument("EnumerationOptions::tolerance must be finite and > 0");
  if (max_size < 0 || max_size > 20)
    throw std::invalid_argument("EnumerationOptions::max_size must be in [0, 20]");
}

Result enumerate(const Problem& p, const EnumerationOptions& options) {
  p.validate();
  options.validate();
  const Eigen::Index n = p.size();
  Result r;
  const SolveClock clock;
  const auto finish = [&](Status s, std::string message) {
    r.status = s;
    evaluate(p, r);
    return clock.finish(r, std::move(message));
  };
  if (n > options.max_size) {
    std::ostringstream s;
    s << "n = " << n << " exceeds the enumeration limit " << options.max_size;
    return finish(Status::kTooLarge, s.str());
  }
  Vector z(n);
  std::vector<Eigen::Index> support;
  support.reserve(static_cast<std::size_t>(n));
  // Supports by increasing size: z = 0 first, so q >= 0 is recognised at once.
  for (Eigen::Index size = 0; size <= n; ++size) {
    if (size == 0) {
      ++r.iterations;
      z.setZero();
      if (residual(p.M, p.q, z) <= options.tolerance) {
        r.z = z;
        return finish(Status::kSolved, "empty support");
      }
      continue;
    }
    // Gosper's hack: the next bit mask with the same number of ones.
    const unsigned long limit = 1ul << n;
    for (unsigned long mask = (1ul << size) - 1; mask < limit;) {
      ++r.iterations;
      support.clear();
      for (Eigen::Index i = 0; i < n; ++i)
        if (mask & (1ul << i)) support.push_back(i);
      const auto k = static_cast<Eigen::Index>(support.size());
      Matrix A(k, k);
      Vector b(k);
      for (Eigen::Index c = 0; c < k; ++c) {
        b(c) = -p.q(support[c]);
        for (Eigen::Index rr = 0; rr < k; ++rr) A(rr, c) = p.M(support[rr], support[c]);
      }
      // The least-norm solve also handles a singular but consistent block.
      const Vector x = A.completeOrthogonalDecomposition().solve(b);
      z.setZero();
      bool nonnegative = x.allFinite();
      for (Eigen::Index c = 0; c < k && nonnegative; ++c) {
        if (x(c) < -options.tolerance * (1.0 + p.q.lpNorm<Eigen::Infinity>())) nonnegative = false;
        z(support[c]) = std::max(0.0, x(c));
      }
      if (nonnegative && residual(p.M, p.q, z) <= options.tolerance) {
        r.z = z;
        return finish(Status::kSolved, "complementary basis found");
      }
      const unsigned long c = mask & (~mask + 1);
      const unsigned long rr = mask + c;
      mask = (((rr ^ mask) >> 2) / c) | rr;
    }
  }
  return finish(Status::kNoSolution, "no complementary basis solves the problem");
}

}  // namespace nsb::lcp
