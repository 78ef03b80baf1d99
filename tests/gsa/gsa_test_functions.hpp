#pragma once
// Analytic test functions of global sensitivity analysis and their exact indices, evaluated
// over gsa designs (rows x D in parameter units).
#include <cmath>
#include <vector>

#include "gsa/sampling.hpp"

namespace gsa_test {

constexpr double kPi = 3.14159265358979323846;

// Ishigami & Homma (1990): f = sin x1 + a sin^2 x2 + b x3^4 sin x1 on [-pi, pi]^3.
struct Ishigami {
  double a = 7.0, b = 0.1;
  double operator()(const double* x) const {
    return std::sin(x[0]) + a * std::sin(x[1]) * std::sin(x[1]) + b * std::pow(x[2], 4) * std::sin(x[0]);
  }
  // Partial variances (Sobol' & Levitan 1999): V1, V2, V13 (V3 = V12 = V23 = V123 = 0).
  double v1() const { return 0.5 * std::pow(1 + b * std::pow(kPi, 4) / 5, 2); }
  double v2() const { return a * a / 8; }
  double v13() const { return b * b * std::pow(kPi, 8) * (1.0 / 18 - 1.0 / 50); }
  double variance() const { return v1() + v2() + v13(); }
  static std::vector<phasmid::gsa::Parameter> parameters() {
    std::vector<phasmid::gsa::Parameter> ps(3);
    for (int j = 0; j < 3; ++j) ps[j].name = "x" + std::to_string(j + 1), ps[j].unit = "1", ps[j].lower = -kPi, ps[j].upper = kPi;
    return ps;
  }
};

// Sobol' G function on [0,1]^D: prod (|4 x_i - 2| + a_i) / (1 + a_i); V_i = 1 / (3 (1 + a_i)^2).
struct GFunction {
  std::vector<double> a;
  double operator()(const double* x) const {
    double g = 1;
    for (std::size_t i = 0; i < a.size(); ++i) g *= (std::fabs(4 * x[i] - 2) + a[i]) / (1 + a[i]);
    return g;
  }
  double vi(std::size_t i) const { return 1.0 / (3 * (1 + a[i]) * (1 + a[i])); }
  double variance() const {
    double p = 1;
    for (std::size_t i = 0; i < a.size(); ++i) p *= 1 + vi(i);
    return p - 1;
  }
  double s1(std::size_t i) const { return vi(i) / variance(); }
  double st(std::size_t i) const { return vi(i) * (variance() + 1) / (1 + vi(i)) / variance(); }
  std::vector<phasmid::gsa::Parameter> parameters() const {
    std::vector<phasmid::gsa::Parameter> ps(a.size());
    for (std::size_t j = 0; j < a.size(); ++j) ps[j].name = "x" + std::to_string(j + 1), ps[j].unit = "1", ps[j].upper = 1;
    return ps;
  }
};

template <class F>
std::vector<double> evaluate(const F& f, const std::vector<double>& values, std::size_t dim) {
  std::vector<double> y(values.size() / dim);
  for (std::size_t i = 0; i < y.size(); ++i) y[i] = f(&values[i * dim]);
  return y;
}

}  // namespace gsa_test
