#include "chi_square.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <vector>

namespace chi2 {
namespace {

constexpr double kPi = std::numbers::pi;

// cos(pi / 2) is 6e-17 in double, not 0: a cell that starts at the horizon would take
// the upper hemisphere's density at its edge, and Simpson's rule weighs that edge.
glm::vec3 direction(double theta, double phi) {
  const double z = std::cos(theta);
  return glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                   std::abs(z) < 1e-12 ? 0.0f : float(z));
}

// Adaptive Simpson's rule in one dimension (pbrt-v4's AdaptiveSimpson).
template <typename F>
double simpson(const F& f, double a, double b, double eps, int depth) {
  struct Step {
    static double run(const F& f, double a, double b, double fa, double fm, double fb, double whole, double eps,
                      int depth) {
      const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
      const double flm = f(lm), frm = f(rm);
      const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
      const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
      const double delta = left + right - whole;
      if (depth <= 0 || std::abs(delta) <= 15.0 * eps) return left + right + delta / 15.0;
      return run(f, a, m, fa, flm, fm, left, eps / 2.0, depth - 1) + run(f, m, b, fm, frm, fb, right, eps / 2.0, depth - 1);
    }
  };
  const double fa = f(a), fb = f(b), fm = f(0.5 * (a + b));
  return Step::run(f, a, b, fa, fm, fb, (b - a) / 6.0 * (fa + 4.0 * fm + fb), eps, depth);
}

// The regularised lower incomplete gamma function P(a, x) (Numerical Recipes 6.2):
// the series below a + 1, the continued fraction above.
double lowerGammaP(double a, double x) {
  if (x <= 0.0) return 0.0;
  const double lnPrefix = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 100000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-15) break;
    }
    return sum * std::exp(lnPrefix);
  }
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-15) break;
  }
  return 1.0 - std::exp(lnPrefix) * h;
}

}  // namespace

double sidak(double alpha, int tests) { return 1.0 - std::pow(1.0 - alpha, 1.0 / double(tests)); }

Result test(const SampleFn& sample, const PdfFn& pdf, int sampleCount, int thetaRes, int phiRes, unsigned seed) {
  const std::size_t cells = std::size_t(thetaRes) * std::size_t(phiRes);
  std::vector<double> observed(cells, 0.0), expected(cells, 0.0);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  Result result;
  for (int i = 0; i < sampleCount; ++i) {
    glm::vec3 w;
    const glm::vec2 u(uniform(rng), uniform(rng));
    if (!sample(u, &w)) continue;
    if (!std::isfinite(w.x) || std::abs(glm::length(w) - 1.0f) > 1e-3f) {
      result.message = "a sample is not a unit direction";
      return result;
    }
    const double theta = std::acos(std::clamp(double(w.z), -1.0, 1.0));
    double phi = std::atan2(double(w.y), double(w.x));
    if (phi < 0.0) phi += 2.0 * kPi;
    const int t = std::clamp(int(theta / kPi * thetaRes), 0, thetaRes - 1);
    const int p = std::clamp(int(phi / (2.0 * kPi) * phiRes), 0, phiRes - 1);
    observed[std::size_t(t) * std::size_t(phiRes) + std::size_t(p)] += 1.0;
  }
  const double dTheta = kPi / thetaRes, dPhi = 2.0 * kPi / phiRes;
  for (int t = 0; t < thetaRes; ++t) {
    for (int p = 0; p < phiRes; ++p) {
      const double theta0 = t * dTheta, phi0 = p * dPhi;
      const auto overTheta = [&](double theta) {
        const auto overPhi = [&](double phi) { return pdf(direction(theta, phi)); };
        return simpson(overPhi, phi0, phi0 + dPhi, 1e-6, 6) * std::sin(theta);
      };
      expected[std::size_t(t) * std::size_t(phiRes) + std::size_t(p)] =
          simpson(overTheta, theta0, theta0 + dTheta, 1e-6, 6) * sampleCount;
    }
  }
  // Cells in order of expected count; those under 5 pooled into one.
  std::vector<std::size_t> order(cells);
  for (std::size_t i = 0; i < cells; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });
  double pooledObserved = 0.0, pooledExpected = 0.0, chsq = 0.0;
  int pooledCells = 0, dof = 0;
  for (const std::size_t i : order) {
    if (expected[i] == 0.0) {
      if (observed[i] > sampleCount * 1e-5) {
        std::ostringstream os;
        os << observed[i] << " samples in cell " << i << " where the pdf is zero";
        result.message = os.str();
        return result;
      }
    } else if (expected[i] < 5.0) {
      pooledObserved += observed[i];
      pooledExpected += expected[i];
      ++pooledCells;
    } else if (pooledCells > 0 && pooledExpected < 5.0) {
      // Keep pooling until the pool itself expects 5.
      pooledObserved += observed[i];
      pooledExpected += expected[i];
      ++pooledCells;
    } else {
      const double diff = observed[i] - expected[i];
      chsq += diff * diff / expected[i];
      ++dof;
    }
  }
  if (pooledExpected > 0.0 || pooledObserved > 0.0) {
    const double diff = pooledObserved - pooledExpected;
    chsq += pooledExpected > 0.0 ? diff * diff / pooledExpected : 1e30;
    ++dof;
  }
  --dof;
  result.statistic = chsq;
  result.degreesOfFreedom = dof;
  result.pValue = dof > 0 ? 1.0 - lowerGammaP(dof / 2.0, chsq / 2.0) : 0.0;
  std::ostringstream os;
  os << "chi^2 = " << chsq << " with " << dof << " degrees of freedom, p = " << result.pValue;
  result.message = os.str();
  return result;
}

}  // namespace chi2
