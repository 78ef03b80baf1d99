#include "features/step_cycles.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "common/format.hpp"

namespace phasmid::features {
namespace {


double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void check_order(const std::vector<Stance>& s, const std::string& what) {
  for (size_t i = 0; i < s.size(); ++i) {
    const std::string at = what + ": stance " + std::to_string(i + 1);
    if (std::isfinite(s[i].touchdown_ms) && std::isfinite(s[i].liftoff_ms) && s[i].liftoff_ms <= s[i].touchdown_ms)
      throw Error(at + " lifts off (" + format_g(s[i].liftoff_ms) + " ms) before it touches down (" + format_g(s[i].touchdown_ms) + " ms)");
    if (i == 0) continue;
    const double prev = std::isfinite(s[i - 1].liftoff_ms) ? s[i - 1].liftoff_ms : s[i - 1].touchdown_ms;
    if (std::isfinite(prev) && std::isfinite(s[i].touchdown_ms) && s[i].touchdown_ms < prev)
      throw Error(at + " touches down (" + format_g(s[i].touchdown_ms) + " ms) before the previous stance ends (" + format_g(prev) + " ms)");
  }
}

// Rules 1-2: every touchdown-to-touchdown interval, dropped when incomplete.
std::vector<Step> candidate_steps(const std::vector<double>& t, const std::vector<std::string>& names,
                                  const std::vector<std::vector<double>>& x, const std::vector<Stance>& s) {
  std::vector<Step> steps;
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    Step st{s[i].touchdown_ms, s[i].liftoff_ms, s[i + 1].touchdown_ms, ""};
    if (!std::isfinite(st.touchdown_ms) || !std::isfinite(st.next_touchdown_ms)) continue;
    if (!std::isfinite(st.liftoff_ms)) st.dropped = "no lift-off";
    // The samples interpolation uses: those inside the step and one on either side.
    auto lo = std::upper_bound(t.begin(), t.end(), st.touchdown_ms);
    auto hi = std::lower_bound(t.begin(), t.end(), st.next_touchdown_ms);
    const size_t a = lo == t.begin() ? 0 : static_cast<size_t>(lo - t.begin()) - 1;
    const size_t b = std::min(t.size() - 1, static_cast<size_t>(hi - t.begin()));
    if (t.empty() || st.touchdown_ms < t.front() || st.next_touchdown_ms > t.back()) st.dropped = "outside the samples";
    for (size_t c = 0; c < x.size(); ++c)
      for (size_t k = a; st.dropped.empty() && k <= b; ++k)
        if (!std::isfinite(x[c][k])) st.dropped = "missing samples in " + names[c];
    steps.push_back(st);
  }
  return steps;
}

// Rules 3-4 on the steps that passed 1-2.
void drop_transient_and_outliers(std::vector<Step>& steps, const StepCycleOptions& o) {
  int left = o.discard_steps;
  std::vector<double> periods;
  for (auto& st : steps) {
    if (!st.dropped.empty()) continue;
    if (left > 0) {
      st.dropped = "start transient";
      --left;
    } else {
      periods.push_back(st.period_ms());
    }
  }
  if (periods.empty()) return;
  const double m = median(periods);
  for (auto& st : steps)
    if (st.dropped.empty() && std::abs(st.period_ms() - m) > o.max_period_deviation * m)
      st.dropped = "period outlier: " + format_g(st.period_ms()) + " ms is more than " + format_g(100 * o.max_period_deviation) +
                   " % from the median " + format_g(m) + " ms";
}

double interpolate(const std::vector<double>& t, const std::vector<double>& x, double at) {
  auto it = std::lower_bound(t.begin(), t.end(), at);
  if (it == t.end()) return x.back();
  const size_t k = static_cast<size_t>(it - t.begin());
  if (k == 0 || t[k] == at) return x[k];
  const double w = (at - t[k - 1]) / (t[k] - t[k - 1]);
  return (1 - w) * x[k - 1] + w * x[k];
}

void mean_sd(const std::vector<double>& v, double& mean, double& sd) {
  double s = 0;
  for (double a : v) s += a;
  mean = s / static_cast<double>(v.size());
  double q = 0;
  for (double a : v) q += (a - mean) * (a - mean);
  sd = v.size() > 1 ? std::sqrt(q / static_cast<double>(v.size() - 1)) : std::nan("");
}

// "; 5 missing samples in L2.ctr, 1 start transient": the reasons, counted, for the error.
std::string why_none(const std::vector<Step>& steps) {
  std::vector<std::pair<std::string, int>> counts;
  for (const auto& st : steps) {
    const std::string why = st.dropped.substr(0, st.dropped.find(':'));
    auto it = std::find_if(counts.begin(), counts.end(), [&](const auto& c) { return c.first == why; });
    if (it == counts.end()) counts.emplace_back(why, 1);
    else ++it->second;
  }
  std::string s;
  for (const auto& [why, n] : counts) s += (s.empty() ? ": " : ", ") + std::to_string(n) + " " + why;
  return s;
}

}  // namespace

std::string StepCycleOptions::invalid_reason() const {
  if (bins < 2) return "bins must be >= 2 (is " + std::to_string(bins) + ")";
  if (discard_steps < 0) return "discard_steps must be >= 0 (is " + std::to_string(discard_steps) + ")";
  if (!(max_period_deviation > 0)) return "max_period_deviation must be > 0 (is " + format_g(max_period_deviation) + ")";
  return "";
}

size_t StepCycles::kept() const {
  return static_cast<size_t>(std::count_if(steps.begin(), steps.end(), [](const Step& s) { return s.dropped.empty(); }));
}

std::vector<Stance> stances_from_contact(const std::vector<double>& t, const std::vector<double>& c) {
  std::vector<Stance> out;
  const double nan = std::nan("");
  for (size_t k = 0; k < c.size(); ++k) {
    const bool on = c[k] == 1, was = k > 0 && c[k - 1] == 1;
    if (on && !was) out.push_back({k == 0 ? nan : 0.5 * (t[k - 1] + t[k]), nan});
    if (!on && was) out.back().liftoff_ms = 0.5 * (t[k - 1] + t[k]);
  }
  return out;
}

StepCycles step_cycles(const std::vector<double>& t, const std::vector<std::string>& channels,
                       const std::vector<std::vector<double>>& x, const std::vector<Stance>& stances,
                       const StepCycleOptions& o, const std::string& what) {
  if (const std::string why = o.invalid_reason(); !why.empty()) throw Error(what + ": " + why);
  check_order(stances, what);
  StepCycles r;
  r.channels = channels;
  r.steps = candidate_steps(t, channels, x, stances);
  drop_transient_and_outliers(r.steps, o);
  std::vector<double> periods, duty;
  for (const auto& st : r.steps)
    if (st.dropped.empty()) periods.push_back(st.period_ms()), duty.push_back(st.duty_factor());
  if (periods.empty())
    throw Error(what + ": no step left of " + std::to_string(r.steps.size()) + " touchdown-to-touchdown intervals" +
                why_none(r.steps) + " (step rules: docs/recordings.md)");
  r.median_period_ms = median(periods);
  mean_sd(periods, r.mean_period_ms, r.period_sd_ms);
  mean_sd(duty, r.duty_factor, r.duty_factor_sd);
  for (int k = 0; k < o.bins; ++k) r.phase.push_back((k + 0.5) / o.bins);
  for (const auto& ch : x) {
    std::vector<double> mean(o.bins), sd(o.bins), at;
    for (int k = 0; k < o.bins; ++k) {
      at.clear();
      for (const auto& st : r.steps)
        if (st.dropped.empty()) at.push_back(interpolate(t, ch, st.touchdown_ms + r.phase[k] * st.period_ms()));
      mean_sd(at, mean[k], sd[k]);
    }
    r.mean_deg.push_back(std::move(mean));
    r.sd_deg.push_back(std::move(sd));
  }
  return r;
}

}  // namespace phasmid::features
