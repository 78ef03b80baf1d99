// phasmid._core.fit and phasmid._core.sweep: the analyses of `phasmid fit` and `phasmid sweep`
// on a scenario's config, writing the same HDF5 file through the same writers; the Python
// layer reads that file into its result objects (docs/python.md).
#include <map>

#include "app/write_output.hpp"
#include "bindings.hpp"
#include "config/sweep_inputs.hpp"
#include "fit/fit_problem.hpp"
#include "fit/fit_run.hpp"
#include "fit/fit_spec.hpp"
#include "io/h5_file.hpp"
#include "solver/interrupt.hpp"
#include "sweep/sweep_runner.hpp"

namespace phasmid::python {
namespace {

// Keyword overrides of phasmid.fit(), the names of `phasmid fit`'s options.
fit::FitOverrides fit_overrides(const std::map<std::string, py::object>& o) {
  fit::FitOverrides ov;
  for (const auto& [key, value] : o) {
    if (key == "data") ov.data = value.cast<std::string>();
    else if (key == "data_format") ov.data_format = value.cast<std::string>();
    else if (key == "parameters") ov.parameters = value.cast<std::string>();
    else if (key == "optimizer") ov.optimizer = value.cast<std::string>();
    else if (key == "multistart") ov.multistart = value.cast<long>();
    else if (key == "seed") ov.seed = value.cast<long>();
    else if (key == "target_set") ov.target_set = value.cast<std::string>();
    else if (key == "max_iterations") ov.max_iterations = value.cast<long>();
    else if (key == "threads") ov.threads = value.cast<int>();
    else
      throw ConfigError("fit: unknown option '" + key +
                        "' (data, data_format, parameters, optimizer, multistart, seed, target_set, max_iterations, threads)");
  }
  return ov;
}

// Runs the fit of the scenario's [fit] section and writes `out`; returns the best start's
// convergence, termination and the summary `phasmid fit` prints.
py::dict run_fit(const std::shared_ptr<PyScenario>& s, const std::map<std::string, py::object>& options,
                 const std::vector<std::string>& profile, const std::string& out) {
  const fit::FitOverrides ov = fit_overrides(options);
  fit::FitSpec spec;
  std::unique_ptr<fit::ResidualProblem> problem = config_stage([&] { return s->scenario->make_fit(s->cfg, ov, spec); });
  spec.optimizer.progress = false;
  if (!profile.empty()) spec.profile = profile;
  std::string text;
  fit::FitSummary best;
  without_gil([&] {
    io::H5Writer w(out);
    fit::FitResult result = fit::run_fit(*problem, spec);
    // Interrupted evaluations count as failed ones inside the optimiser; the fit is not a result.
    if (solver::interrupt_requested()) throw solver::Interrupted("fit interrupted");
    app::write_run_file(w, s->cfg, s->sets, *s->scenario);
    fit::write_fit_h5(w, *problem, spec, result);
    w.commit();
    text = fit::format_result(*problem, result);
    best = result.best();
  });
  py::dict d;
  d["converged"] = best.converged;
  d["usable"] = best.usable;
  d["termination"] = best.termination;
  d["message"] = best.message;
  d["summary"] = text;
  return d;
}

// Runs every point of the config's [sweep] and writes `out`; Ctrl-C finishes the running
// points and raises KeyboardInterrupt (the journal `out`.journal keeps the finished ones).
py::dict run_sweep(const std::shared_ptr<PyScenario>& s, int threads, bool resume, const std::string& out) {
  sweep::SweepInputs inputs = config_stage([&] { return config::sweep_inputs(s->cfg, s->sets); });
  sweep::SweepOptions o;
  o.output = out;
  o.threads = threads;
  o.resume = resume;
  o.progress = false;
  o.handle_signals = true;
  o.command = command_text();
  sweep::SweepOutcome r;
  {
    py::gil_scoped_release release;
    r = sweep::run_sweep(std::move(inputs), o);
  }
  if (r.signal) {
    PyErr_SetString(PyExc_KeyboardInterrupt, ("sweep interrupted with " + std::to_string(r.n_recovered + r.n_computed) +
                                              " of " + std::to_string(r.n_points) + " points done (kept in " + r.journal +
                                              "; resume=True continues)").c_str());
    throw py::error_already_set();
  }
  py::dict d;
  d["n_points"] = r.n_points;
  d["n_failed"] = r.n_failed;
  d["n_recovered"] = r.n_recovered;
  d["executor"] = r.executor;
  d["wall_seconds"] = r.wall_seconds;
  return d;
}

}  // namespace

void bind_analyses(py::module_& m) {
  m.def("fit", &run_fit, py::arg("scenario"), py::arg("options"), py::arg("profile"), py::arg("out"));
  m.def("sweep", &run_sweep, py::arg("scenario"), py::arg("threads"), py::arg("resume"), py::arg("out"));
}

}  // namespace phasmid::python
