#include "sample/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "common/error.hpp"

namespace phasmid::sample {

namespace {
double mean(const std::vector<double>& v, size_t from = 0, size_t to = std::string::npos) {
  to = std::min(to, v.size());
  double s = 0;
  for (size_t i = from; i < to; ++i) s += v[i];
  return s / static_cast<double>(to - from);
}

// Biased (1/n) autocovariance of v at lag t.
double autocovariance(const std::vector<double>& v, double m, size_t t) {
  double s = 0;
  for (size_t i = 0; i + t < v.size(); ++i) s += (v[i] - m) * (v[i + t] - m);
  return s / static_cast<double>(v.size());
}

void check_chains(const Chains& chains) {
  if (chains.empty() || chains[0].size() < 4) throw Error("diagnostics need at least one chain of 4 draws");
  for (const auto& c : chains)
    if (c.size() != chains[0].size()) throw Error("diagnostics need chains of equal length");
}

// W (mean within-chain variance) and var+ (Gelman et al.'s pooled estimate).
std::pair<double, double> within_and_pooled(const Chains& chains) {
  const double n = static_cast<double>(chains[0].size());
  const double m = static_cast<double>(chains.size());
  std::vector<double> means;
  double w = 0;
  for (const auto& c : chains) {
    const double mc = mean(c);
    means.push_back(mc);
    w += autocovariance(c, mc, 0) * n / (n - 1);
  }
  w /= m;
  double b_over_n = 0;
  if (chains.size() > 1) {
    const double grand = mean(means);
    for (double mc : means) b_over_n += (mc - grand) * (mc - grand);
    b_over_n /= (m - 1);
  }
  return {w, (n - 1) / n * w + b_over_n};
}
}  // namespace

Moments moments(const std::vector<double>& v) {
  const double m = mean(v), n = static_cast<double>(v.size());
  return {m, autocovariance(v, m, 0) * n / (n - 1)};
}

double effective_sample_size(const Chains& chains) {
  check_chains(chains);
  const size_t n = chains[0].size();
  const double total = static_cast<double>(n * chains.size());
  const std::pair<double, double> pooled = within_and_pooled(chains);  // no structured binding: the lambda
  const double w = pooled.first, var_plus = pooled.second;                // below captures them (clang 14)
  if (!(var_plus > 0)) return std::numeric_limits<double>::quiet_NaN();  // a constant chain
  std::vector<double> means;
  for (const auto& c : chains) means.push_back(mean(c));
  auto rho = [&](size_t t) {
    double g = 0;
    for (size_t c = 0; c < chains.size(); ++c) g += autocovariance(chains[c], means[c], t);
    g /= static_cast<double>(chains.size());
    return 1.0 - (w - g) / var_plus;
  };
  // Geyer: pairs P_k = rho(2k) + rho(2k+1) while positive, made monotone non-increasing.
  double tau = -1.0, previous = std::numeric_limits<double>::infinity();
  for (size_t k = 0; 2 * k + 1 < n; ++k) {
    double p = rho(2 * k) + rho(2 * k + 1);
    if (!(p > 0)) break;
    p = std::min(p, previous);
    previous = p;
    tau += 2.0 * p;
  }
  // Antithetic chains can give tau < 1; Stan caps the ESS at total * log10(total).
  tau = std::max(tau, 1.0 / std::log10(total));
  return total / tau;
}

double split_rhat(const Chains& chains) {
  check_chains(chains);
  const size_t half = chains[0].size() / 2;
  Chains halves;
  for (const auto& c : chains) {
    halves.emplace_back(c.begin(), c.begin() + static_cast<long>(half));
    halves.emplace_back(c.end() - static_cast<long>(half), c.end());
  }
  const auto [w, var_plus] = within_and_pooled(halves);
  if (!(w > 0)) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(var_plus / w);
}

double geweke_z(const std::vector<double>& chain) {
  const size_t n = chain.size();
  const size_t a = std::max<size_t>(n / 10, 4), b = n - n / 2;
  if (a >= b || n - b < 4) return std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> first(chain.begin(), chain.begin() + static_cast<long>(a));
  const std::vector<double> last(chain.begin() + static_cast<long>(b), chain.end());
  // Under the hypothesis tested (a stationary chain) both parts have the spectral density at
  // zero of the last half, S(0) = variance x integrated autocorrelation time; taking the first
  // part's own would let the drift under test inflate its variance and hide itself.
  const double s0 = autocovariance(last, mean(last), 0) * static_cast<double>(last.size()) / effective_sample_size({last});
  const double v = s0 * (1.0 / static_cast<double>(first.size()) + 1.0 / static_cast<double>(last.size()));
  if (!(v > 0)) return std::numeric_limits<double>::quiet_NaN();
  return (mean(first) - mean(last)) / std::sqrt(v);
}

double normal_two_sided_quantile(double alpha) {
  // Bisection on erfc(z / sqrt 2) = alpha: monotone, 200 halvings reach double precision.
  double lo = 0, hi = 40;
  for (int i = 0; i < 200; ++i) {
    const double z = 0.5 * (lo + hi);
    (std::erfc(z / std::sqrt(2.0)) > alpha ? lo : hi) = z;
  }
  return 0.5 * (lo + hi);
}

size_t burn_in(const std::vector<Chains>& draws) {
  if (draws.empty() || draws[0].empty()) return 0;
  const size_t n = draws[0][0].size();
  const double tests = static_cast<double>(draws.size() * draws[0].size());
  const double z_max = normal_two_sided_quantile(0.05 / tests);
  for (size_t k = 1; k < 20; ++k) {
    const size_t start = k * n / 20;
    bool stationary = true;
    for (const Chains& p : draws)
      for (const auto& c : p) {
        const double z = geweke_z(std::vector<double>(c.begin() + static_cast<long>(start), c.end()));
        // A constant tail (NaN z: a chain that never moved) is not evidence of stationarity.
        stationary = stationary && std::abs(z) <= z_max;
      }
    if (stationary) return start;
  }
  return n;
}

std::vector<std::string> diagnostic_warnings(const std::string& parameter, double ess, double rhat) {
  std::vector<std::string> w;
  auto fmt = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", v);
    return std::string(b);
  };
  if (!(rhat <= 1.01)) w.push_back(parameter + ": split R-hat " + fmt(rhat) + " > 1.01: the chains disagree; run longer");
  if (!(ess >= 100)) w.push_back(parameter + ": effective sample size " + fmt(ess) + " < 100: too few independent draws");
  return w;
}

}  // namespace phasmid::sample
