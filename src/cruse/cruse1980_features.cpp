#include "cruse/cruse1980_features.hpp"

#include <algorithm>
#include <cmath>

namespace phasmid::cruse {
namespace {

// Timestamps of the same raster instant are identical; in event-exact runs they agree to
// rounding. This separates "simultaneous" from "following".
constexpr double kSameInstantMs = 1e-6;

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

// Mean time from each onset of `hind` in [from, to) to the next onset of `front` after it; a
// front onset within `simultaneous` of the hind onset is simultaneous, not following.
double graham_lag(const std::vector<double>& hind, const std::vector<double>& front, double from, double to,
                  double simultaneous) {
  std::vector<double> lags;
  for (double th : hind) {
    if (th < from - simultaneous || th >= to - simultaneous) continue;
    auto it = std::upper_bound(front.begin(), front.end(), th + simultaneous);
    if (it != front.end()) lags.push_back(*it - th);
  }
  return mean(lags);
}

}  // namespace

Features measure(const Trajectory& run, const Parameters& p) {
  Features f;
  const auto& lead = run.onsets_ms[L1];
  const int cycles = static_cast<int>(p.get("analysis.cycles"));
  // Need the window plus one OL1 onset after it so that lags into the next cycle exist.
  if (static_cast<int>(lead.size()) < cycles + 2) return f;
  const std::size_t last = lead.size() - 2;  // window = [lead[last - cycles], lead[last])
  const double from = lead[last - cycles], to = lead[last];
  f.period_ms = (to - from) / cycles;

  f.locked = true;
  const auto& names = leg_names();
  const double tol = p.get("analysis.in_phase_tolerance_ms");
  // Window edges sit half a tolerance before OL1 onsets, so that legs protracting together
  // with OL1 (give or take the tolerance) are counted in the same cycle as OL1.
  const double edge = 0.5 * tol + kSameInstantMs;
  std::array<std::vector<double>, kLegCount> window;
  for (int leg = 0; leg < kLegCount; ++leg) {
    for (double t : run.onsets_ms[leg])
      if (t >= from - edge && t < to - edge) window[leg].push_back(t);
    if (static_cast<int>(window[leg].size()) != cycles) {
      f.locked = false;
      continue;
    }
    std::vector<double> phases;
    for (double t : window[leg]) {
      auto it = std::upper_bound(lead.begin(), lead.end(), t + edge);
      const double prev = *(it - 1);
      phases.push_back((t - prev) / f.period_ms);
    }
    f.phase[leg] = mean(phases);
  }
  f.lag_L3_L1_ms = graham_lag(run.onsets_ms[L3], lead, from, to, edge);
  f.lag_R3_R1_ms = graham_lag(run.onsets_ms[R3], run.onsets_ms[R1], from, to, edge);

  for (int a = 0; a < kLegCount; ++a)
    for (int b = a + 1; b < kLegCount; ++b) {
      if (window[a].size() != static_cast<std::size_t>(cycles) || window[b].size() != window[a].size()) continue;
      bool together = true;
      for (double ta : window[a]) {
        double nearest = 1e300;
        for (double tb : run.onsets_ms[b]) nearest = std::min(nearest, std::abs(tb - ta));
        together = together && nearest <= tol + kSameInstantMs;
      }
      if (together) f.in_phase_pairs.push_back(names[a] + "-" + names[b]);
    }
  return f;
}

bool in_phase(const Features& f, const std::string& pair) {
  return std::find(f.in_phase_pairs.begin(), f.in_phase_pairs.end(), pair) != f.in_phase_pairs.end();
}

bool same_pattern(const Features& a, const Features& b, double tolerance_ms) {
  if (!a.locked || !b.locked) return false;
  if (std::abs(a.period_ms - b.period_ms) > tolerance_ms) return false;
  for (int leg = 0; leg < kLegCount; ++leg) {
    double d = std::abs(a.phase[leg] - b.phase[leg]);
    d = std::min(d, 1.0 - d);  // phases are circular
    if (d * a.period_ms > tolerance_ms) return false;
  }
  return true;
}

}  // namespace phasmid::cruse
