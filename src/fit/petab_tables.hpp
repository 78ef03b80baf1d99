#pragma once
// A recording fit as PEtab tables (docs/recordings.md, "PEtab tables"), next to the parameter
// table (fit/parameter_table.hpp):
//  - observables: one row per recorded angle, observableFormula "sign * scale * <leg>.<joint> +
//    offset" (scale and offset numbers or parameter ids), noiseFormula a number, a noise
//    parameter id, or noiseParameter1_<id> (the measurements' noiseParameters: the animal's
//    step-to-step SD per bin); and per recording "period_ms(<leg>)" and "duty_factor(<leg>)";
//  - measurements: per phase bin the animal's mean angle at time = phase x the mean period (ms
//    after touchdown), and the period and duty factor at time inf (the steady gait), each with
//    its noise;
//  - conditions: one row per condition (fit/condition_problem.hpp), one column per model
//    parameter a condition sets (a number or a parameter id; empty: not set).
// format_petab writes them from recording targets; parse_petab reads them back into the same
// targets and conditions (a round trip gives the same residuals). Names are phasmid's (dotted
// model parameters and angles), which PEtab tools that require SBML identifiers must rename.
#include <string>
#include <vector>

#include "fit/condition_problem.hpp"
#include "fit/targets.hpp"

namespace phasmid::fit {

// noiseFormula of an observable whose noise is each measurement's noiseParameters.
inline constexpr const char* kPetabNoisePlaceholder = "noiseParameter1_";

struct PetabTables {
  std::string observables, measurements, conditions;  // TSV texts
};

// Throws Error naming the target if it is not a recording ([[fit.recording]]).
PetabTables format_petab(const Targets& targets, const std::vector<Condition>& conditions);

// The recordings and conditions of the tables; origins name file:line. sample_ms is the model
// outputs' spacing of the step-cycle targets (StepCycleTarget::sample_ms). Errors are one line.
struct PetabInput {
  std::string observables, measurements, conditions;  // texts
  std::string observables_origin, measurements_origin, conditions_origin;  // file names
};
void parse_petab(const PetabInput& in, double sample_ms, Targets& targets, std::vector<Condition>& conditions);

}  // namespace phasmid::fit
