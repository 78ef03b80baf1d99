// phasmid._core: the C++ half of the phasmid Python module (bindings.hpp, docs/python.md).
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <mutex>

#include "bindings.hpp"
#include "build_info.hpp"
#include "io/output_lock.hpp"
#include "io/output_path.hpp"
#include "output/run_file.hpp"
#include "report/report.hpp"
#include "solver/interrupt.hpp"

namespace phasmid::python {
namespace {
std::mutex g_guard_mutex;
int g_guards = 0;
struct sigaction g_python_handler;

extern "C" void on_sigint(int) { solver::request_interrupt(); }
}  // namespace

InterruptGuard::InterruptGuard() {
  std::lock_guard<std::mutex> lock(g_guard_mutex);
  if (g_guards++ > 0) return;
  solver::clear_interrupt();
  struct sigaction sa {};
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &g_python_handler);
}

InterruptGuard::~InterruptGuard() {
  std::lock_guard<std::mutex> lock(g_guard_mutex);
  if (--g_guards > 0) return;
  sigaction(SIGINT, &g_python_handler, nullptr);
  solver::clear_interrupt();  // so that later runs outside a guard (sweeps) are not stopped
}

std::string command_text() { return std::string("phasmid ") + PHASMID_VERSION + " Python module"; }

py::array view(const double* data, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides, py::handle base) {
  py::array a(py::dtype::of<double>(), std::move(shape), std::move(strides), data, base);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::array view(const std::vector<double>& v, py::handle base) {
  return view(v.data(), {static_cast<py::ssize_t>(v.size())}, {sizeof(double)}, base);
}

std::shared_ptr<PyScenario> make_scenario(config::Config cfg, std::vector<std::string> sets) {
  auto s = std::make_shared<PyScenario>();
  s->cfg = std::move(cfg);
  s->sets = std::move(sets);
  config_stage([&] {
    s->scenario = config::build_scenario(s->cfg, s->sets);
    s->settings = config::simulation_settings(s->cfg, s->scenario.get());
  });
  return s;
}

namespace {

// FileResult.save: the bytes of a file the C++ core wrote, written as io::H5Writer writes (after
// the output-path check with the result's inputs, into "<out>.tmp", renamed onto `out` when
// complete, the .tmp removed on failure). One place for every byte-copy save from Python.
// Writes as the C++ writers do: the output-path check, the output's lock (io::OutputLock, so a
// second writer of OUT is refused before it touches a file), "<out>.tmp", then the rename. The
// lock removes "<out>.tmp" if anything fails before the rename.
void save_bytes(const std::string& out, const std::string& content, const std::vector<std::string>& inputs) {
  io::check_output_path(out, inputs);
  io::HeldOutputLock lock(out);
  const std::string& tmp = lock.get().tmp_path();
  auto fail = [&](const std::string& what) { throw Error("cannot " + what + " " + tmp + ": " + std::strerror(errno)); };
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) fail("write");
  for (size_t done = 0; done < content.size();) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int e = errno;
      ::close(fd);
      errno = e;
      fail("write");
    }
    done += static_cast<size_t>(n);
  }
  if (::close(fd) != 0) fail("write");
  lock.get().publish(false);
}

void bind_errors(py::module_& m) {
  static py::exception<Error> error(m, "Error");
  static py::exception<ConfigError> config_error(m, "ConfigError", error.ptr());
  static py::exception<SolverError> solver_error(m, "SolverError", error.ptr());
  // Translators run newest first: the most derived kinds are registered last.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const solver::Interrupted& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const ConfigError& e) {
      config_error(e.what());
    } catch (const SolverError& e) {
      solver_error(e.what());
    } catch (const Error& e) {
      error(e.what());
    }
  });
}
}  // namespace
}  // namespace phasmid::python

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using namespace phasmid::python;
  m.doc() = "C++ core of the phasmid Python module; use the phasmid package (docs/python.md).";
  m.attr("__version__") = PHASMID_VERSION;
  // The `command` attribute of the files the module writes: there is no command line.
  phasmid::output::set_command_line(command_text());
  bind_errors(m);
  bind_scenario(m);
  bind_sensitivity(m);
  bind_analyses(m);
  m.def("save_bytes", [](const std::string& out, const py::bytes& content, const std::vector<std::string>& inputs) {
    std::string bytes = content;  // copied with the GIL held; written without it
    py::gil_scoped_release release;
    save_bytes(out, bytes, inputs);
  }, py::arg("out"), py::arg("content"), py::arg("inputs"), "Write a file's bytes as the C++ writers write an output.");
  m.def("write_report", [](const std::string& h5, const std::string& html) {
    phasmid::report::write_report(h5, html);
  }, py::arg("h5_path"), py::arg("html_path"), "Write the HTML report of a phasmid HDF5 file (phasmid report).");
}
