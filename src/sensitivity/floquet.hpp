#pragma once
// Limit-cycle analysis: monodromy matrix, Floquet multipliers and phase response curves.
//
// The monodromy matrix Phi(T) = dy(t0 + T)/dy(t0) along a periodic orbit is obtained
// exactly from CVODES forward sensitivities: InitialValueModel shifts the state by
// parameters delta (x = y - delta, x' = f(t0 + t, x + delta, p), delta = 0), so the
// sensitivities with respect to delta are dx/ddelta = Phi - I (the model's templated
// right-hand side gives J Phi column by column through Jet directional derivatives).
#include <complex>
#include <vector>

#include <Eigen/Dense>

#include "model/ode_model.hpp"
#include "solver/simulator.hpp"

namespace phasmid::io {
class H5Writer;
}

namespace phasmid::sensitivity {

// `base` started at state y0 at time t0, with sensitivities of the initial state available
// as the parameters "delta.<state name>" (after the base model's parameters).
class InitialValueModel : public model::OdeModelT<InitialValueModel> {
 public:
  InitialValueModel(const model::OdeModel& base, std::vector<double> y0, double t0);
  std::string kind() const override { return "initial_value(" + base_.kind() + ")"; }
  std::vector<double> initial_state(const std::vector<double>& p) const override;
  std::vector<double> breakpoints(const std::vector<double>& p, double t_end) const override;
  size_t num_base_parameters() const { return nb_; }
  // The parameter vector: the base model's followed by delta = 0.
  std::vector<double> extend(const std::vector<double>& p_base) const;

  template <class T>
  void eval(double t, const T* x, const T* p, T* xdot) const {
    thread_local std::vector<T> y;
    const size_t n = num_states();
    y.resize(n);
    for (size_t i = 0; i < n; ++i) y[i] = x[i] + p[nb_ + i];
    base_.rhs(t0_ + t, y.data(), p, xdot);
  }

 private:
  const model::OdeModel& base_;
  std::vector<double> y0_;
  double t0_;
  size_t nb_;
};

struct FloquetOptions {
  // Poincare section: an event of this root in its direction (+1 or -1) starts each cycle.
  solver::RootSpec section{0, 0.0, -1};
  double transient_ms = 5000.0;   // integrate this long before measuring the cycle
  double max_period_ms = 2000.0;  // upper bound on the period (search window after the transient)
  solver::SolverOptions solver;
};

// Section at the maxima of the first joint angle (its velocity falling through zero).
solver::RootSpec default_section(const model::OdeModel& model);

struct PeriodicOrbit {
  double t0 = 0.0;         // time of the section crossing the orbit starts from (ms)
  double period_ms = 0.0;  // time to the next crossing
  std::vector<double> y0;  // state on the section
};

// Locates the orbit by integrating past the transient; the last two section crossings give
// the period. Throws Error if fewer than two crossings occur.
PeriodicOrbit find_periodic_orbit(const model::OdeModel& model, const std::vector<double>& p,
                                  const FloquetOptions& options);

struct FloquetResult {
  PeriodicOrbit orbit;
  Eigen::MatrixXd monodromy;                  // Phi(T), n x n
  std::vector<std::complex<double>> multipliers;  // eigenvalues of Phi(T), by decreasing modulus
  double closure_error = 0.0;                 // max |y(t0 + T) - y0| (how periodic the orbit is)
  // For an autonomous limit cycle one multiplier is 1 (perturbation along the orbit); this is
  // the distance of the multiplier closest to 1 from 1.
  double trivial_multiplier_error = 0.0;
  // Accuracy of Phi itself, independent of how periodic the orbit is: for an autonomous system
  // Phi(T) f(y(t0)) = f(y(t0 + T)) exactly; this is |Phi f0 - f1| / |f1| (Euclidean norms).
  double flow_identity_error = 0.0;
  double seconds = 0.0;        // wall time of the monodromy run (sensitivities w.r.t. all states)
  solver::SolverStats monodromy_stats;
};

// Monodromy matrix over one period along `orbit`, by forward sensitivities; `y_end` (if
// given) receives the state after one period and `stats` the solver statistics.
Eigen::MatrixXd monodromy_matrix(const model::OdeModel& model, const std::vector<double>& p, const PeriodicOrbit& orbit,
                                 const solver::SolverOptions& solver_options, std::vector<double>* y_end = nullptr,
                                 solver::SolverStats* stats = nullptr);

FloquetResult floquet_analysis(const model::OdeModel& model, const std::vector<double>& p,
                               const FloquetOptions& options = {});

struct PrcOptions {
  size_t state = 0;         // perturbed state
  double amplitude = 1e-3;  // size of the brief (instantaneous) perturbation, in the state's unit
  size_t n_phases = 20;     // perturbation phases k / n_phases, k = 0..n_phases-1
  int cycles_after = 5;     // cycles to let the perturbation decay before measuring the phase
  FloquetOptions floquet;
};

struct PhaseResponseCurve {
  PeriodicOrbit orbit;
  std::vector<double> phase;  // phase of the perturbation (cycles, 0 = section crossing)
  std::vector<double> shift;  // asymptotic phase shift (cycles; positive = advance)
};

// Phase response curve to an instantaneous kick `amplitude` of one state at n_phases phases.
PhaseResponseCurve phase_response_curve(const model::OdeModel& model, const std::vector<double>& p,
                                        const PrcOptions& options);

// /sensitivity/floquet/{period_ms, monodromy, multipliers_real, multipliers_imag,
// multipliers_abs, closure_error, state_on_section}
void write_floquet_h5(io::H5Writer& out, const model::OdeModel& model, const FloquetResult& result);
// /sensitivity/prc/{phase, shift} with attributes state, amplitude
void write_prc_h5(io::H5Writer& out, const model::OdeModel& model, const PrcOptions& options,
                  const PhaseResponseCurve& prc);

}  // namespace phasmid::sensitivity
