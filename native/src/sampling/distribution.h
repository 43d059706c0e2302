#pragma once
// Piecewise-constant distributions on [0,1) and [0,1)^2 (pbrt's Distribution1D/2D),
// with pdf and inverse, used to importance-sample environment maps.
#include <vector>

#include "math/vec.h"

namespace fenestra {

class Distribution1D {
 public:
  Distribution1D() = default;
  // `weights` must be non-negative; an all-zero function is sampled uniformly.
  explicit Distribution1D(std::vector<double> weights);

  int size() const { return static_cast<int>(func_.size()); }
  double integral() const { return integral_; }
  // Continuous sample in [0,1); `index` is the cell it falls in; pdf is the density on [0,1).
  float sample(float u, int* index, float* pdf) const;
  float pdf(float x) const;
  float to_unit(float x) const;  // inverse of sample(): CDF(x)
  float cell_pdf(int index) const { return static_cast<float>(func_[index] / normaliser_); }

 private:
  // Cell with the largest cdf <= the next value below (what std::upper_bound would find).
  int cell_of(double u) const;

  std::vector<double> func_, cdf_;
  // guide_[j]: the largest i with cdf_[i] <= j / size(): the cell of u lies between guide_[j] and
  // guide_[j + 1] for j = floor(u * size()), so a search is short whatever the size.
  std::vector<int> guide_;
  double integral_ = 0.0, normaliser_ = 1.0;
};

class Distribution2D {
 public:
  Distribution2D() = default;
  // Row-major `weights` (height rows of width values); rows are v, columns u.
  Distribution2D(const std::vector<double>& weights, int width, int height);

  Vec2 sample(const Vec2& u, float* pdf) const;  // returns (x, y) in [0,1)^2
  float pdf(const Vec2& p) const;
  Vec2 to_unit(const Vec2& p) const;  // inverse of sample()
  double integral() const { return marginal_.integral(); }

 private:
  int width_ = 0, height_ = 0;
  std::vector<Distribution1D> conditional_;
  Distribution1D marginal_;
};

}  // namespace fenestra
