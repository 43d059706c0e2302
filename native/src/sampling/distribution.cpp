#include "sampling/distribution.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fenestra {

Distribution1D::Distribution1D(std::vector<double> weights) : func_(std::move(weights)) {
  const int n = size();
  if (n == 0) throw std::invalid_argument("Distribution1D: no cells");
  double sum = 0.0;
  for (double w : func_) {
    if (!(w >= 0.0) || !std::isfinite(w)) throw std::invalid_argument("Distribution1D: weights must be finite and >= 0");
    sum += w;
  }
  integral_ = sum / n;
  if (sum <= 0.0) std::fill(func_.begin(), func_.end(), 1.0), sum = n;
  normaliser_ = sum / n;  // func / normaliser is a density on [0,1)
  cdf_.assign(n + 1, 0.0);
  for (int i = 0; i < n; ++i) cdf_[i + 1] = cdf_[i] + func_[i] / sum;
  cdf_[n] = 1.0;
  guide_.assign(n + 1, 0);
  for (int j = 0, i = 0; j <= n; ++j) {
    const double x = static_cast<double>(j) / n;
    while (i < n && cdf_[i + 1] <= x) ++i;
    guide_[j] = i;
  }
}

int Distribution1D::cell_of(double u) const {
  const int n = size();
  if (!(u >= 0.0 && u < 1.0))
    return static_cast<int>(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin()) - 1;
  const int j = std::min(static_cast<int>(u * n), n - 1);
  int lo = guide_[j], hi = std::min(guide_[j + 1], n - 1);
  while (lo > 0 && cdf_[lo] > u) --lo;  // u * n rounded up to the next integer
  while (hi < n && cdf_[hi + 1] <= u) ++hi;
  return static_cast<int>(std::upper_bound(cdf_.begin() + lo + 1, cdf_.begin() + hi + 1, u) - cdf_.begin()) - 1;
}

float Distribution1D::sample(float u, int* index, float* pdf) const {
  const int n = size();
  // Largest i with cdf[i] <= u, skipping zero-width cells.
  int i = std::clamp(cell_of(static_cast<double>(u)), 0, n - 1);
  while (i < n - 1 && func_[i] == 0.0) ++i;
  const double width = cdf_[i + 1] - cdf_[i];
  double du = width > 0.0 ? (u - cdf_[i]) / width : 0.5;
  du = std::clamp(du, 0.0, std::nextafter(1.0, 0.0));
  if (index) *index = i;
  if (pdf) *pdf = static_cast<float>(func_[i] / normaliser_);
  float x = std::min(static_cast<float>((i + du) / n), std::nextafter(1.0f, 0.0f));
  // Rounding to float can carry x across a cell edge; keep it in cell i as pdf() locates it.
  while (x > 0.0f && static_cast<int>(x * n) > i) x = std::nextafter(x, 0.0f);
  while (x < 1.0f && static_cast<int>(x * n) < i) x = std::nextafter(x, 1.0f);
  return x;
}

float Distribution1D::pdf(float x) const {
  const int i = std::clamp(static_cast<int>(x * size()), 0, size() - 1);
  return static_cast<float>(func_[i] / normaliser_);
}

float Distribution1D::to_unit(float x) const {
  const int n = size();
  const double cell = std::clamp(static_cast<double>(x) * n, 0.0, static_cast<double>(n));
  const int i = std::min(static_cast<int>(cell), n - 1);
  return static_cast<float>(cdf_[i] + (cell - i) * (cdf_[i + 1] - cdf_[i]));
}

Distribution2D::Distribution2D(const std::vector<double>& weights, int width, int height)
    : width_(width), height_(height) {
  if (width <= 0 || height <= 0 || weights.size() != static_cast<size_t>(width) * height)
    throw std::invalid_argument("Distribution2D: weights do not match width x height");
  std::vector<double> row_integrals(height);
  conditional_.reserve(height);
  for (int y = 0; y < height; ++y) {
    conditional_.emplace_back(std::vector<double>(weights.begin() + static_cast<size_t>(y) * width,
                                                  weights.begin() + static_cast<size_t>(y + 1) * width));
    row_integrals[y] = conditional_.back().integral();
  }
  marginal_ = Distribution1D(std::move(row_integrals));
}

Vec2 Distribution2D::sample(const Vec2& u, float* pdf) const {
  int row = 0;
  float pdf_row = 0.0f, pdf_col = 0.0f;
  const float y = marginal_.sample(u.y(), &row, &pdf_row);
  const float x = conditional_[row].sample(u.x(), nullptr, &pdf_col);
  if (pdf) *pdf = pdf_row * pdf_col;
  return Vec2(x, y);
}

float Distribution2D::pdf(const Vec2& p) const {
  const int row = std::clamp(static_cast<int>(p.y() * height_), 0, height_ - 1);
  return marginal_.pdf(p.y()) * conditional_[row].pdf(p.x());
}

Vec2 Distribution2D::to_unit(const Vec2& p) const {
  const int row = std::clamp(static_cast<int>(p.y() * height_), 0, height_ - 1);
  return Vec2(conditional_[row].to_unit(p.x()), marginal_.to_unit(p.y()));
}

}  // namespace fenestra
