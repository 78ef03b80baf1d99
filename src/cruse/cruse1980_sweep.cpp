#include "cruse/cruse1980_sweep.hpp"

#include <cmath>
#include <limits>

#include "cruse/cruse1980_features.hpp"
#include "cruse/cruse1980_model.hpp"

namespace phasmid::cruse {
namespace {

constexpr double kSweepCycles = 60;

std::vector<double> grid(double from, double to, double step) {
  std::vector<double> v;
  for (int i = 0; from + i * step <= to + 1e-9; ++i) v.push_back(std::round((from + i * step) * 1e6) / 1e6);
  return v;
}

}  // namespace

double retraction_rate_for_period(const Parameters& p, double period_ms) {
  const double amplitude = p.t0(L1);
  if (p.gait == Gait::I)  // P = A/v (1 + 1/k)
    return amplitude * (1.0 + 1.0 / p.get("gait1.protraction_to_retraction_rate")) / period_ms;
  return amplitude / (period_ms - amplitude / p.get("protraction_rate"));
}

Parameters at_period(const Parameters& base, double period_ms, double cycles) {
  Parameters p = base;
  p.set("retraction_rate", retraction_rate_for_period(base, period_ms));
  p.set("duration_ms", cycles * period_ms);
  return p;
}

bool is_stable(const Parameters& base, const std::vector<double>& periods_ms) {
  const double tol = base.get("analysis.in_phase_tolerance_ms");
  for (double period : periods_ms) {
    // Give every speed the same number of cycles to settle (docs/cruse1980.md).
    Parameters p = at_period(base, period, kSweepCycles);
    Features first;
    for (int start = 1; start <= 10; ++start) {
      p.set("start_position", start);
      const Features f = measure(simulate(p), p);
      if (!f.locked || !in_phase(f, "L1-R2") || !in_phase(f, "L2-R3")) return false;
      if (start == 1) first = f;
      else if (!same_pattern(first, f, tol)) return false;
    }
  }
  return true;
}

SweepAxis sweep_axis(const Parameters& base, const std::string& parameter, const std::vector<double>& values,
                     const std::vector<double>& periods_ms) {
  SweepAxis axis;
  axis.parameter = parameter;
  axis.values = values;
  for (double v : values) {
    Parameters p = base;
    p.set(parameter, v);
    axis.stable.push_back(is_stable(p, periods_ms) ? 1 : 0);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  axis.stable_min = axis.stable_max = nan;
  int runs = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!axis.stable[i]) continue;
    if (std::isnan(axis.stable_min)) axis.stable_min = values[i];
    axis.stable_max = values[i];
    if (i == 0 || !axis.stable[i - 1]) ++runs;
  }
  axis.contiguous = runs == 1;
  return axis;
}

std::vector<SweepAxis> sweep_table1(const Parameters& base, const std::vector<double>& periods_ms) {
  std::vector<SweepAxis> axes;
  const auto t0_grid = grid(9.8, 10.8, 0.05);
  for (int leg = L2; leg < kLegCount; ++leg) axes.push_back(sweep_axis(base, "T0." + leg_names()[leg], t0_grid, periods_ms));
  axes.push_back(sweep_axis(base, "T1", grid(0.5, 10.5, 0.25), periods_ms));
  axes.push_back(sweep_axis(base, "T2", grid(0.25, 11.0, 0.25), periods_ms));
  return axes;
}

}  // namespace phasmid::cruse
