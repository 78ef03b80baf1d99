#include "solver/step_history.hpp"

#include <algorithm>

#include "common/error.hpp"

namespace phasmid::solver {

void StepHistory::record(double t0, double tn, const double* y0, const double* f0, const double* yn,
                         const double* fn) {
  if ((!y0 || !f0) && steps_.empty()) throw Error("internal: StepHistory::record without start values");
  Step s;
  s.t0 = y0 ? t0 : steps_.back().tn;  // no gap of a rounding error between the two
  s.tn = tn;
  if (!spare_.empty()) {
    s.v = std::move(spare_.back());
    spare_.pop_back();
  }
  s.v.resize(4 * n_);
  const double* prev = steps_.empty() ? nullptr : steps_.back().v.data();
  std::copy(y0 ? y0 : prev + 2 * n_, (y0 ? y0 : prev + 2 * n_) + n_, s.v.begin());
  std::copy(f0 ? f0 : prev + 3 * n_, (f0 ? f0 : prev + 3 * n_) + n_, s.v.begin() + static_cast<long>(n_));
  std::copy(yn, yn + n_, s.v.begin() + static_cast<long>(2 * n_));
  std::copy(fn, fn + n_, s.v.begin() + static_cast<long>(3 * n_));
  steps_.push_back(std::move(s));
}

bool StepHistory::at(double t, const std::vector<size_t>& index, double* row) const {
  for (auto it = steps_.rbegin(); it != steps_.rend(); ++it) {
    if (t < it->t0 || t > it->tn) continue;
    const double h = it->tn - it->t0;
    const double* y0 = it->v.data();
    const double *f0 = y0 + n_, *yn = y0 + 2 * n_, *fn = y0 + 3 * n_;
    if (h <= 0.0) {
      for (size_t i = 0; i < n_; ++i) row[index[i]] = yn[i];
      return true;
    }
    // Cubic Hermite basis at theta = (t - t0) / h.
    const double th = (t - it->t0) / h, u = 1.0 - th;
    const double a0 = (1.0 + 2.0 * th) * u * u, b0 = h * th * u * u;
    const double a1 = th * th * (3.0 - 2.0 * th), b1 = -h * th * th * u;
    for (size_t i = 0; i < n_; ++i) row[index[i]] = a0 * y0[i] + b0 * f0[i] + a1 * yn[i] + b1 * fn[i];
    return true;
  }
  return false;
}

void StepHistory::drop_before(double t) {
  while (steps_.size() > 1 && steps_.front().tn < t) {
    spare_.push_back(std::move(steps_.front().v));
    steps_.pop_front();
  }
}

void StepHistory::drop_from(double t) {
  while (!steps_.empty() && steps_.back().t0 >= t) {
    spare_.push_back(std::move(steps_.back().v));
    steps_.pop_back();
  }
}

}  // namespace phasmid::solver
