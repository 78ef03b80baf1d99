#pragma once
// Shared pieces of the phasmid Python module (docs/python.md): the scenario a Python object
// holds, the error kinds, running C++ with the GIL released and Ctrl-C turned into an
// interrupt request, and NumPy views of memory owned by a C++ result.
//
// Contract:
//  - Arrays handed to Python view the C++ result's memory (no copy); their `base` is the
//    Python object owning that result, which stays alive as long as any view does.
//  - Every call that integrates releases the GIL (threads run scenarios in parallel) and,
//    while it runs, SIGINT requests solver::request_interrupt(); the run then ends within one
//    solver step and KeyboardInterrupt is raised.
//  - Errors keep the C++ one-line message; errors of reading a config are ConfigError.
//  - Every file written (save, report, out=) first passes io::check_output_path with the
//    files the result came from (PyScenario::inputs, a fit's data files), as the CLI's verbs do.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "config/config.hpp"
#include "scenario/scenario.hpp"

namespace phasmid::python {
namespace py = pybind11;

// An error in a config, a --set-like override or a section of it (raised as phasmid.ConfigError).
class ConfigError : public Error {
 public:
  explicit ConfigError(const std::string& message) : Error(message) {}
};

// Runs f() and turns any phasmid::Error (not a SolverError) into a ConfigError.
template <class F>
auto config_stage(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const SolverError&) {
    throw;
  } catch (const ConfigError&) {
    throw;
  } catch (const Error& e) {
    throw ConfigError(e.what());
  }
}

// While alive: SIGINT requests an interrupt of the runs in progress (nested and concurrent
// guards share one handler; the last one restores Python's).
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
};

// f() with the GIL released and Ctrl-C turned into an interrupt request.
template <class F>
auto without_gil(F&& f) -> decltype(f()) {
  InterruptGuard guard;
  py::gil_scoped_release release;
  return f();
}

// A scenario as Python sees it: the config, the overrides given so far, and the model built
// from them (shared by every result run from it, so results keep their model alive).
struct PyScenario {
  config::Config cfg;
  std::vector<std::string> sets;
  std::shared_ptr<scenario::Scenario> scenario;
  config::SimulationSettings settings;
  // The files a result of this scenario comes from (its config, where it is one on disk): an
  // output may not be one of them (io::check_output_path).
  std::vector<std::string> inputs() const { return {cfg.path}; }
};
std::shared_ptr<PyScenario> make_scenario(config::Config cfg, std::vector<std::string> sets);

// A read-only NumPy view of `data` with the given shape and byte strides, owned by `base`.
py::array view(const double* data, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides, py::handle base);
// A 1-D view of a whole vector.
py::array view(const std::vector<double>& v, py::handle base);

// The `command` attribute of files written from Python.
std::string command_text();

void bind_scenario(py::module_& m);
void bind_sensitivity(py::module_& m);
void bind_analyses(py::module_& m);

}  // namespace phasmid::python
