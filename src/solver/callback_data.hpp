#pragma once
// The whole-system driver's link to CVODES (solver/simulator.cpp): the data its C callbacks
// share for one run, and the callbacks themselves: the right-hand side, the roots, the
// Jacobian by forward-mode AD (dense, band, or sparse with a coloured pattern for KLU) and the
// forward sensitivities' right-hand sides in Jet chunks.
#include <cvodes/cvodes.h>

#include <memory>
#include <vector>

#include "model/ode_model.hpp"
#include "solver/cvodes_session.hpp"
#include "solver/run_parameters.hpp"
#include "solver/solver_options.hpp"
#include "solver/solver_result.hpp"

namespace phasmid::solver::whole_system {

using model::Jet1;
using model::Jet4;
using model::JetK;

// Scratch vectors of one scalar type for model evaluations: states, parameters (their values;
// derivative lanes are seeded and cleared around each evaluation) and right-hand side.
template <class J>
struct JetScratch {
  std::vector<J> y, p, f;
  void init(size_t n, const std::vector<double>& values) {
    y.assign(n, J(0.0));
    f.assign(n, J(0.0));
    p.clear();
    for (double v : values) p.emplace_back(v);
  }
};

// Everything the C callbacks need; lives for one run().
struct CallbackData {
  const model::OdeModel* model;
  const std::vector<double>* p;             // the run's parameters (RunParameters::values)
  std::unique_ptr<model::OdeModelPart> eq;  // the model bound to *p (make_whole), or none
  const std::vector<RootSpec>* roots;
  std::vector<size_t> sens_params;
  size_t n;
  JetScratch<JetK> jK;  // Jacobian columns, sensitivity chunks of five to eight
  JetScratch<Jet4> j4;  // sensitivity chunks of two to four
  JetScratch<Jet1> j1;  // one sensitivity
  // The scratch vectors; their parameters mirror the run's (kept in step by `params`).
  void init_scratch(RunParameters& params) {
    jK.init(n, params.values());
    j4.init(n, params.values());
    j1.init(n, params.values());
    params.mirror(jK.p);
    params.mirror(j4.p);
    params.mirror(j1.p);
  }
  long sens_evals = 0;
  // Sparse (KLU) Jacobians: column-compressed pattern and a column colouring (columns of one
  // colour share no row, so one AD direction per colour gives all of them: Curtis-Powell-Reid).
  std::vector<sunindextype> col_ptr, row_idx;
  std::vector<size_t> color;
  size_t n_colors = 0;
};

// CVRhsFn and CVRootFn of the whole model (user data: CallbackData).
int rhs_cb(sunrealtype t, N_Vector y, N_Vector ydot, void* ud);
int root_cb(sunrealtype t, N_Vector y, sunrealtype* g, void* ud);
// The Newton linear system of the whole model (SolverOptions::linear_solver, Auto by size);
// the KLU path needs the Jacobian's sparsity pattern, computed here into d.
void attach_linear_solver(CvodesSession& session, CallbackData& d, const model::OdeModel& model,
                          const SolverOptions& options, const std::vector<double>& y0, size_t ns);
// Forward sensitivities from s(0) = dy0/dp (central differences of the initial state).
void init_sensitivities(CvodesSession& session, const model::OdeModel& model, const std::vector<double>& p,
                        const std::vector<size_t>& sens_params);

}  // namespace phasmid::solver::whole_system
