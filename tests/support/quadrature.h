#pragma once
// Adaptive Simpson quadrature in double, for the tests that hold a Monte Carlo
// estimate or a density against its integral (phase functions, single scattering):
// each interval is halved until its two halves agree with the whole to `tolerance`
// (shared among the halves), or `depth` halvings are spent.
#include <cmath>

namespace engine::test {

namespace detail {
template <typename F>
double simpsonStep(const F& f, double a, double b, double fa, double fm, double fb, double whole, double tolerance,
                   int depth) {
  const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm), right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
  if (depth <= 0 || std::abs(left + right - whole) <= 15.0 * tolerance) return left + right + (left + right - whole) / 15.0;
  return simpsonStep(f, a, m, fa, flm, fm, left, 0.5 * tolerance, depth - 1) +
         simpsonStep(f, m, b, fm, frm, fb, right, 0.5 * tolerance, depth - 1);
}
}  // namespace detail

// The integral of f over [a, b].
template <typename F>
double integrate(const F& f, double a, double b, double tolerance, int depth = 30) {
  const double fa = f(a), fm = f(0.5 * (a + b)), fb = f(b);
  return detail::simpsonStep(f, a, b, fa, fm, fb, (b - a) / 6.0 * (fa + 4.0 * fm + fb), tolerance, depth);
}

}  // namespace engine::test
