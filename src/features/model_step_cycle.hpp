#pragma once
// The model's step cycle of one contact leg, summarised as `phasmid steps` summarises a
// recording (features/step_cycles.hpp, docs/recordings.md), with derivatives: a fit compares
// the two. Touch-downs and lift-offs are the located ground-contact events after the
// transient, debounced as the per-leg features count them; a step runs from one touch-down to
// the next with a lift-off between. The angle at phase phi of a step [td, td + T] is the
// output interpolated linearly at td + phi T, so its derivative is the interpolated
// sensitivity plus the interpolant's slope times d(td + phi T)/dp. Means over the steps.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "features/features.hpp"
#include "model/ode_model.hpp"
#include "solver/solver_result.hpp"

namespace phasmid::features {

struct ModelStepCycle {
  size_t steps = 0;
  std::vector<double> phase;          // bin centres (k + 1/2) / bins
  std::vector<size_t> channels;       // angle channels of the leg (model.angles() indices)
  std::vector<std::vector<double>> mean_deg;              // per channel, per bin
  std::vector<std::vector<Eigen::VectorXd>> dmean_deg;    // the same, d/dp (res.sens_params), when with_grad
  double period_ms = 0, duty_factor = 0;                  // means over the steps
  Eigen::VectorXd dperiod_ms, dduty_factor;
};

// Needs a run with feature_roots located (first in its root list, or at opt.root_offset) and
// outputs dense enough to interpolate over the steps; with_grad needs sensitivities at the
// outputs and events. Throws Error "<leg>: ..." when the leg has no contact, or fewer than one
// complete step after opt.discard_ms.
ModelStepCycle model_step_cycle(const model::OdeModel& model, const solver::SolveResult& res, const std::string& leg,
                                int bins, const FeatureOptions& opt, bool with_grad);

}  // namespace phasmid::features
