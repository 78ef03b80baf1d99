#pragma once
// Sensitivities of the steady gait (docs/sensitivity.md, "Steady-cycle sensitivities"): the
// derivatives of the converged periodic orbit and of every gait feature on it with respect to
// the model's parameters, exact up to the integration tolerances and with no averaging window.
//
// The cycle (y0 on the section s, period T) solves F(y0, T, p) = (y(T; y0, p) - y0, y0[s] - level)
// = 0 (Newton shooting, continuation/shooting.hpp). By the implicit function theorem
//   [Phi - I   f(y(T))] [dy0/dp]   [-dy(T)/dp]
//   [e_s^T        0   ] [dT/dp ] = [    0    ]
// with Phi the monodromy (saltation terms at switches included) and dy(T)/dp the forward
// sensitivities of one period from y0 at fixed y0. The features are then computed on
// feature_cycles periods of the converged cycle by a forward-sensitivity run whose initial
// sensitivities are dy0/dp: the run follows the perturbed cycle itself, so each event time's
// derivative is that of the steady cycle (events of cycle k move by k dT/dp plus their phase's
// change) and the feature gradients (event-time formula) are the steady gait's.
//
// Cost: Newton's monodromy runs (n sensitivities over one period, usually once or twice), then
// np sensitivities over 1 + feature_cycles periods, after one plain transient.
//
// A model whose commands at fixed times continue after the transient (a joint forced by a
// switch schedule) has no free cycle: analyse_cycle_sensitivities refuses it in one line.
// A cycle that does not close (no rhythm, spikes that slip from cycle to cycle, quasi-periodic
// drift) makes Newton fail: analyse_cycle_sensitivities throws one line naming the section,
// Newton's residual and the cycle-to-cycle spread of the period after the transient. A cycle of
// a family (a further multiplier at 1: legs whose relative phase nothing pulls back) has no
// unique derivative: the same, naming the multipliers.
#include <complex>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/error.hpp"
#include "continuation/shooting.hpp"
#include "sensitivity/sensitivity.hpp"

namespace phasmid::continuation {

// The model has no steady cycle to differentiate (the cases the header names); the message is
// the one line for the user. Every other Error (an unknown parameter, a failed run) is not this.
class NoSteadyCycle : public Error {
 public:
  explicit NoSteadyCycle(const std::string& message) : Error(message) {}
};

struct CycleSensitivityOptions {
  CycleSensitivityOptions() { shooting.tolerance = 1e-3; }
  // Section, transient, Newton's tolerance; its solver is the sensitivity runs' own
  // (SensitivityOptions::solver, tightened to max_rtol), set by analyse_cycle_sensitivities.
  // Newton's tolerance is in state units (mV, rad, ...): an error of the cycle's state enters
  // the derivatives only at second order, and the residual of a neural network's cycle stalls
  // at its integration noise (about 1e-4 mV at rtol 1e-8), so 1e-3 is the default.
  ShootingOptions shooting;
  // The runs of the cycle integrate at this relative tolerance or tighter (atol scaled alike):
  // the derivatives of event-defined features are only as accurate as the event times.
  double max_rtol = 1e-8;
  double feature_cycles = 3.0;  // periods of the converged cycle the features are computed on
};

struct CycleSensitivity {
  sensitivity::SensitivityReport report;  // features on the converged cycle and their derivatives
  Cycle cycle;
  NewtonReport newton;
  std::vector<std::complex<double>> multipliers;  // of the converged cycle, by decreasing modulus
  std::string section;         // e.g. "middle.fti.omega falling through 0"
  double residual = 0.0;      // max |y(T) - y0| at the converged cycle (state units)
  Eigen::RowVectorXd dperiod;  // dT/dp_j, ms per parameter unit (report.parameters' order)
  Eigen::MatrixXd dstate;      // dy0_i/dp_j on the section (states x parameters)
};

// The section a model's cycle is measured on by default: sensitivity::default_section (the
// maxima of its first joint angle).
CycleSensitivityOptions default_cycle_options(const model::OdeModel& model);

// Steady-cycle sensitivities of the parameters options.parameters (empty: all but triggered
// command times), by forward sensitivities (Method::Forward) or by central differences of the
// converged cycle's features (Method::FiniteDifference: Newton from the nominal cycle at
// p -+ h for each parameter). Throws Error as the header says.
CycleSensitivity analyse_cycle_sensitivities(const model::OdeModel& model, const std::vector<double>& p,
                                             const sensitivity::SensitivityOptions& options,
                                             CycleSensitivityOptions cycle_options);

// The gait features on feature_cycles periods of the cycle through `guess` at parameters p
// (Newton from guess, then a plain run): the values analyse_cycle_sensitivities differentiates.
std::vector<features::Feature> cycle_features(const model::OdeModel& model, const std::vector<double>& p,
                                              const Cycle& guess, const CycleSensitivityOptions& options);

// /sensitivity/cycle/{period_ms, dperiod, state_on_section, dstate, multipliers_real,
// multipliers_imag, multipliers_abs} with attributes residual, newton_iterations, section
// (docs/hdf5.md).
void write_cycle_h5(io::H5Writer& out, const model::OdeModel& model, const CycleSensitivity& result);

}  // namespace phasmid::continuation
