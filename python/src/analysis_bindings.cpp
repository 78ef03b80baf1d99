// phasmid._core.fit, .sweep and .gsa: the analyses of `phasmid fit`, `phasmid sweep` and
// `phasmid gsa` on a scenario's config, writing the same HDF5 file through the same writers; the Python
// layer reads that file into its result objects (docs/python.md).
#include <limits>
#include <map>

#include "output/run_file.hpp"
#include "bindings.hpp"
#include "config/gsa_inputs.hpp"
#include "gsa/summary.hpp"
#include "config/sweep_inputs.hpp"
#include "parallel/executor.hpp"
#include "config/fit_section.hpp"
#include "fit/fit_problem.hpp"
#include "fit/fit_run.hpp"
#include "fit/fit_spec.hpp"
#include "io/h5_file.hpp"
#include "io/output_path.hpp"
#include "solver/interrupt.hpp"
#include "sweep/sweep_runner.hpp"

namespace phasmid::python {
namespace {

// A keyword's value as the message shows it: repr, cut short (10**400 has 401 digits).
std::string shown(py::handle v) {
  std::string r = py::repr(v).cast<std::string>();
  if (r.size() > 40) r = r.substr(0, 37) + "...";
  return r;
}

long integer_option(const std::string& key, py::handle v) {
  if (py::isinstance<py::int_>(v) && !py::isinstance<py::bool_>(v)) {
    try {
      return v.cast<long>();
    } catch (const py::cast_error&) {
    }
  }
  throw ConfigError("fit(): '" + key + "' must be an integer (a 64-bit one), got " + shown(v));
}

std::string text_option(const std::string& key, py::handle v) {
  if (!py::isinstance<py::str>(v)) throw ConfigError("fit(): '" + key + "' must be a string, got " + shown(v));
  return v.cast<std::string>();
}

// Keyword overrides of phasmid.fit(), the names of `phasmid fit`'s options; their ranges are
// checked by fit::check_overrides, as the CLI's are.
fit::FitOverrides fit_overrides(const std::map<std::string, py::object>& o) {
  fit::FitOverrides ov;
  for (const auto& [key, value] : o) {
    if (key == "data") ov.data = text_option(key, value);
    else if (key == "data_format") ov.data_format = text_option(key, value);
    else if (key == "parameters") ov.parameters = text_option(key, value);
    else if (key == "optimizer") ov.optimizer = text_option(key, value);
    else if (key == "multistart") ov.multistart = integer_option(key, value);
    else if (key == "seed") ov.seed = integer_option(key, value);
    else if (key == "target_set") ov.target_set = text_option(key, value);
    else if (key == "max_iterations") ov.max_iterations = integer_option(key, value);
    else if (key == "threads") {
      const long t = integer_option(key, value);
      if (t < std::numeric_limits<int>::min() || t > std::numeric_limits<int>::max())
        throw ConfigError("-j/--threads " + std::to_string(t) + ": at most " + std::to_string(parallel::kMaxThreads));
      ov.threads = static_cast<int>(t);
    } else
      throw ConfigError("fit: unknown option '" + key +
                        "' (data, data_format, parameters, optimizer, multistart, seed, target_set, max_iterations, threads)");
  }
  config_stage([&] {
    fit::check_overrides(ov);
    parallel::bounded_threads(ov.threads);
  });
  return ov;
}

// Runs the fit of the scenario's [fit] section and writes `out`; returns the best start's
// convergence, termination, the summary `phasmid fit` prints and the files the fit read (the
// config, data and parameter files: a later save() may not overwrite them).
py::dict run_fit(const std::shared_ptr<PyScenario>& s, const std::map<std::string, py::object>& options,
                 const std::vector<std::string>& profile, const std::string& out) {
  const fit::FitOverrides ov = fit_overrides(options);
  fit::FitSpec spec = config_stage([&] { return config::fit_spec(s->cfg, *s->scenario, ov); });
  std::unique_ptr<fit::ResidualProblem> problem = config_stage([&] { return s->scenario->make_fit(spec); });
  spec.optimizer.progress = false;
  if (!profile.empty()) spec.profile = profile;
  std::vector<std::string> inputs = spec.inputs;
  inputs.push_back(s->cfg.path);
  io::check_output_path(out, inputs);
  std::string text;
  fit::FitSummary best;
  without_gil([&] {
    io::H5Writer w(out);
    fit::FitResult result = fit::run_fit(*problem, spec);
    // Interrupted evaluations count as failed ones inside the optimiser; the fit is not a result.
    if (solver::interrupt_requested()) throw solver::Interrupted("fit interrupted");
    output::write_run_file(w, s->cfg, s->sets, *s->scenario);
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
  d["inputs"] = inputs;
  return d;
}

// A sweep that did not finish: KeyboardInterrupt "<what> interrupted with K of N points done<tail>"
// after Ctrl-C, else (stop_after) phasmid.Error "<what> stopped with ...".
[[noreturn]] void raise_unfinished(const std::string& what, const sweep::SweepOutcome& r, const std::string& tail) {
  const std::string text = what + (r.signal ? " interrupted" : " stopped") + " with " +
                           std::to_string(r.n_recovered + r.n_computed) + " of " + std::to_string(r.n_points) +
                           " points done" + tail;
  if (r.signal) {
    PyErr_SetString(PyExc_KeyboardInterrupt, text.c_str());
    throw py::error_already_set();
  }
  throw Error(text);
}

// What is true of an unfinished sweep's journal: with the caller's `out=` it is kept and
// resume=True continues; in the module's temporary directory it is gone with the directory.
std::string unfinished_tail(const std::string& what, bool kept, const sweep::SweepOutcome& r) {
  if (kept) return " (kept in " + r.journal + "; phasmid." + what + "(..., out=\"" + r.output + "\", resume=True) continues)";
  return " (nothing kept: with out=PATH the finished points stay in PATH.journal and resume=True continues)";
}

sweep::SweepOptions sweep_options(int threads, bool resume, const std::string& out, long stop_after) {
  sweep::SweepOptions o;
  o.stop_after = stop_after;
  o.output = out;
  o.threads = threads;
  o.resume = resume;
  o.progress = false;
  o.handle_signals = true;
  o.command = command_text();
  return o;
}

py::dict sweep_outcome(const sweep::SweepOutcome& r) {
  py::dict d;
  d["n_points"] = r.n_points;
  d["n_failed"] = r.n_failed;
  d["n_recovered"] = r.n_recovered;
  d["executor"] = r.executor;
  d["wall_seconds"] = r.wall_seconds;
  return d;
}

// Threads, and `out` (with its journal) checked as the CLI's sweep and gsa check them, before
// any work: an Error (not a ConfigError: nothing of the config is wrong) naming the path.
void check_run(const PyScenario& s, int threads, const std::string& out) {
  config_stage([&] { parallel::bounded_threads(threads); });
  io::check_output_path(out, s.inputs(), {sweep::Journal::path_for(out)});
}

// Runs every point of the config's [sweep] and writes `out`; Ctrl-C finishes the running
// points and raises KeyboardInterrupt (the journal `out`.journal keeps the finished ones;
// `kept`: out is the caller's, so the journal outlives the call).
py::dict run_sweep(const std::shared_ptr<PyScenario>& s, int threads, bool resume, const std::string& out, bool kept,
                   long stop_after) {
  sweep::SweepInputs inputs = config_stage([&] { return config::sweep_inputs(s->cfg, s->sets); });
  check_run(*s, threads, out);
  sweep::SweepOutcome r;
  {
    py::gil_scoped_release release;
    r = sweep::run_sweep(std::move(inputs), sweep_options(threads, resume, out, stop_after));
  }
  if (!r.complete) raise_unfinished("sweep", r, unfinished_tail("sweep", kept, r));
  return sweep_outcome(r);
}

// Runs the config's [gsa] analysis as `phasmid gsa` does (gsa::run_gsa) into `out`; returns
// the sweep's counts and the table the verb prints.
py::dict run_gsa(const std::shared_ptr<PyScenario>& s, int threads, bool resume, const std::string& out, bool kept,
                 long stop_after) {
  const gsa::GsaInputs in = config_stage([&] { return config::gsa_inputs(s->cfg, s->sets); });
  check_run(*s, threads, out);
  gsa::GsaOutcome r;
  {
    py::gil_scoped_release release;
    r = gsa::run_gsa(in, sweep_options(threads, resume, out, stop_after), false);
  }
  if (!r.analysed) raise_unfinished("gsa", r.sweep, unfinished_tail("gsa", kept, r.sweep));
  py::dict d = sweep_outcome(r.sweep);
  d["summary"] = gsa::gsa_summary(r.result);
  return d;
}

}  // namespace

void bind_analyses(py::module_& m) {
  m.def("fit", &run_fit, py::arg("scenario"), py::arg("options"), py::arg("profile"), py::arg("out"));
  m.def("sweep", &run_sweep, py::arg("scenario"), py::arg("threads"), py::arg("resume"), py::arg("out"), py::arg("kept"),
        py::arg("stop_after") = -1);
  m.def("gsa", &run_gsa, py::arg("scenario"), py::arg("threads"), py::arg("resume"), py::arg("out"), py::arg("kept"),
        py::arg("stop_after") = -1);
  m.def("check_output_path", [](const std::string& out, const std::vector<std::string>& inputs) {
    io::check_output_path(out, inputs);
  }, py::arg("out"), py::arg("inputs"), "io::check_output_path: the CLI's check of an output path against its inputs.");
}

}  // namespace phasmid::python
