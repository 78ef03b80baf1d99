#pragma once
// Step cycles of one leg (docs/recordings.md): touchdowns cut a recording, or a simulated
// trajectory, into steps; each step's angles are resampled onto phase 0-1 and the steps are
// summarised by the mean and SD per phase bin, the median step period and the duty factor.
// The same summary is made of an animal and of the model, so that they are compared step
// cycle against step cycle and not clock time against clock time.
//
// Which steps count (the rule users cite as "phasmid's step rule"):
//  1. A step runs from one observed touchdown to the next, with an observed lift-off between
//     them; a stance cut by the start or end of the recording is no touchdown (NaN).
//  2. A step with a missing angle sample (NaN) in any channel is dropped.
//  3. The first `discard_steps` steps that pass 1-2 are dropped as the start transient.
//  4. Of the rest, a step whose period differs from their median by more than
//     `max_period_deviation` (a fraction) is dropped: a pause, a stumble or a missed touchdown.
#include <string>
#include <vector>

namespace phasmid::features {

// One stance: touchdown and lift-off (ms); NaN where the recording does not see it.
struct Stance {
  double touchdown_ms, liftoff_ms;
};

struct StepCycleOptions {
  int bins = 50;                      // phase bins from touchdown (0) to the next touchdown (1)
  int discard_steps = 1;              // rule 3
  double max_period_deviation = 0.3;  // rule 4, fraction of the median period
  // Empty when the options can be used, else why not (one line naming the option).
  std::string invalid_reason() const;
};

struct Step {
  double touchdown_ms, liftoff_ms, next_touchdown_ms;
  std::string dropped;  // empty: kept; else the rule that dropped it
  double period_ms() const { return next_touchdown_ms - touchdown_ms; }
  double duty_factor() const { return (liftoff_ms - touchdown_ms) / period_ms(); }
};

struct StepCycles {
  std::vector<Step> steps;  // every touchdown-to-touchdown interval, kept or dropped
  std::vector<double> phase;  // bin centres, (k + 1/2) / bins
  std::vector<std::string> channels;
  std::vector<std::vector<double>> mean_deg, sd_deg;  // per channel, per bin (SD: n - 1; NaN for one step)
  // Over kept steps. The median is the robust summary; the mean is the fit's (frames quantise
  // every period to whole frames, and the median of quantised periods keeps up to half a
  // frame of bias, where the mean has none).
  double median_period_ms = 0, mean_period_ms = 0, period_sd_ms = 0;
  double duty_factor = 0, duty_factor_sd = 0;         // mean and SD over kept steps
  size_t kept() const;
};

// Stances from a sampled 0/1 contact signal: the touchdown lies between the last sample out of
// contact and the first in contact and is taken halfway between them; the lift-off likewise.
// Contact at the first (last) sample censors that stance's touchdown (lift-off). Values other than 0, 1 and NaN are the caller's to reject.
std::vector<Stance> stances_from_contact(const std::vector<double>& time_ms, const std::vector<double>& contact);

// The summary. `samples[c][k]` is channel c at time_ms[k] (strictly increasing). Throws Error
// "<what>: ..." when the stances are out of order or no step survives the rules.
StepCycles step_cycles(const std::vector<double>& time_ms, const std::vector<std::string>& channels,
                       const std::vector<std::vector<double>>& samples, const std::vector<Stance>& stances,
                       const StepCycleOptions& options, const std::string& what);

}  // namespace phasmid::features
