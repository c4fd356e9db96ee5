#include "raytrace/sampling.h"

#include <algorithm>
#include <cmath>

namespace engine::rt {

Distribution1D::Distribution1D(std::span<const float> weights) : func_(weights.begin(), weights.end()) {
  const std::size_t n = func_.size();
  cdf_.assign(n + 1, 0.0f);
  // Summed in double: a 4096-cell row of tiny and huge texels loses no cell.
  double sum = 0.0;
  std::vector<double> cumulative(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    func_[i] = std::isfinite(func_[i]) ? std::max(func_[i], 0.0f) : 0.0f;
    sum += double(func_[i]);
    cumulative[i + 1] = sum;
  }
  integral_ = n > 0 ? float(sum / double(n)) : 0.0f;
  for (std::size_t i = 1; i <= n; ++i) {
    // All zero: sample uniformly rather than divide by zero.
    cdf_[i] = sum > 0.0 ? float(cumulative[i] / sum) : float(double(i) / double(n));
  }
  if (n > 0) cdf_[n] = 1.0f;
}

float Distribution1D::sample(float u, int* index) const {
  const int n = size();
  // The last cell whose CDF start is <= u (upper_bound minus one), never an empty one
  // at the end: u < 1 and cdf_[n] = 1.
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
  int i = std::clamp(int(it - cdf_.begin()) - 1, 0, n - 1);
  // Skip zero-width cells that u landed on the boundary of.
  while (i < n - 1 && cdf_[std::size_t(i) + 1] <= u) ++i;
  if (index) *index = i;
  const float width = cdf_[std::size_t(i) + 1] - cdf_[std::size_t(i)];
  const float du = width > 0.0f ? (u - cdf_[std::size_t(i)]) / width : 0.5f;
  return std::min((float(i) + std::clamp(du, 0.0f, 1.0f)) / float(n), std::nextafter(1.0f, 0.0f));
}

Distribution2D::Distribution2D(std::span<const float> weights, int width, int height) : width_(width), height_(height) {
  rows_.reserve(std::size_t(height));
  std::vector<float> rowIntegrals(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    rows_.emplace_back(weights.subspan(std::size_t(y) * std::size_t(width), std::size_t(width)));
    rowIntegrals[std::size_t(y)] = rows_.back().integral();
  }
  marginal_ = Distribution1D(rowIntegrals);
}

glm::vec2 Distribution2D::sample(glm::vec2 u, float* pdf) const {
  int row = 0, column = 0;
  const float v = marginal_.sample(u.y, &row);
  const float x = rows_[std::size_t(row)].sample(u.x, &column);
  if (pdf) *pdf = marginal_.pdf(row) * rows_[std::size_t(row)].pdf(column);
  return {x, v};
}

float Distribution2D::pdf(glm::vec2 p) const {
  const int row = std::clamp(int(p.y * float(height_)), 0, height_ - 1);
  const int column = std::clamp(int(p.x * float(width_)), 0, width_ - 1);
  return marginal_.pdf(row) * rows_[std::size_t(row)].pdf(column);
}

}  // namespace engine::rt
