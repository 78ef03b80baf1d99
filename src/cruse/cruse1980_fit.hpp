#pragma once
// `phasmid fit` for the Cruse (1980) model (docs/cruse1980.md, "Fitting the Fig. 3 switch
// curves"): named parameters of a cruse1980 scenario (typically the switch nodes switch.<S>.at_<P>ms)
// are estimated so that Cruse features, measured at given nominal periods from each of the
// given Table 2 starting positions, meet [[fit.feature]] targets. The model is piecewise
// linear with discrete phase decisions, so there is no Jacobian: only derivative-free or
// global NLopt methods apply (ceres is rejected with a one-line error).
#include <memory>
#include <string>
#include <vector>

#include "cruse/cruse1980_features.hpp"
#include "fit/fit_spec.hpp"
#include "fit/residual_problem.hpp"

namespace phasmid::cruse {

// One target: residual = (feature - value) / tolerance.
//  Run features (need period_ms; one residual per starting position):
//    locked (1/0), period_ms, lag_L3_L1_ms, lag_R3_R1_ms,
//    lag_difference_ms (lag_R3_R1_ms - lag_L3_L1_ms), phase.<leg>,
//    gap_ms.<A>-<B> (circular distance of the two legs' onset phases, in ms),
//    pattern_deviation_ms (largest circular phase difference, in ms, of any leg from the
//      pattern of the first listed starting position; 0 for that one),
//    wave_excess_ms (per side, the hind->middle plus middle->front onset delays beyond one
//      period, summed over both sides; 0 when the metachronal wave runs back to front).
//  Parameter features (no period_ms, one residual):
//    switch_reversal.<S> (S = SL, SR, SL1R1): sum over consecutive Fig. 3 nodes of
//      max(0, S(P_i) - S(P_i+1)), in units; 0 when the switch moves anteriorly (to smaller
//      values) as the period shortens.
struct CruseTarget {
  std::string feature;
  double period_ms = 0;  // nominal period of the runs (0 for parameter features)
  double value = 0;
  double tolerance = 1;
  std::string origin;    // config file:line
};

struct CruseFitSettings {
  std::vector<int> start_positions = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  double cycles = 60;  // each run lasts this many nominal periods (as the Table 1 sweep, configs/cruse1980_table1.toml)
};

// Value of a run feature (see CruseTarget). `first` is the run from the first starting position.
double run_feature(const std::string& name, const Features& f, const Features& first);
// Value of a parameter feature.
double parameter_feature(const std::string& name, const Parameters& p);
bool is_run_feature(const std::string& name);
bool is_parameter_feature(const std::string& name);

class CruseFitProblem : public fit::ResidualProblem {
 public:
  // Throws Error for unknown parameters or features, bad tolerances or periods.
  CruseFitProblem(Parameters base, std::vector<fit::FitParameter> parameters, std::vector<CruseTarget> targets,
                  CruseFitSettings settings);

  std::string parameter_unit(size_t j) const override;
  std::vector<std::string> tied_parameters(size_t j) const override;
  bool has_jacobian() const override { return false; }
  std::string no_jacobian_reason() const override;
  bool evaluate(const double* x, double* r, double* J, std::string* error = nullptr) const override;
  // /trajectory, /events, /parameters, /features of the run at the fitted values with the
  // config's own period and starting position, as `phasmid simulate` writes them.
  void write_model_output(io::H5Writer& out, const double* x, bool usable, double output_dt_ms) const override;

  Parameters parameters_at(const double* x) const;  // the base parameters with the estimates set
  const std::vector<CruseTarget>& targets() const { return targets_; }
  const CruseFitSettings& settings() const { return settings_; }

 private:
  Parameters base_;
  std::vector<CruseTarget> targets_;
  CruseFitSettings settings_;
  std::vector<double> periods_;                  // distinct periods of run targets
  std::vector<std::vector<std::string>> tied_;   // per estimated parameter: the names it sets
};

// What [fit] gives a cruse1980 fit besides the common FitSpec (FitSpec::kind; read by
// config/cruse_section.hpp): its targets and how each is run.
struct CruseFitSpec : fit::KindFitSpec {
  std::vector<CruseTarget> targets;
  CruseFitSettings settings;
};

}  // namespace phasmid::cruse
