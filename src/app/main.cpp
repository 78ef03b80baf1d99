// phasmid: one binary, many verbs (see docs/cli.md).
#include <CLI/CLI.hpp>
#include <iostream>

#include "app/verb.hpp"
#include "common/error.hpp"
#include "build_info.hpp"
#include "dist/executor.hpp"
#include "dist/session.hpp"
#include "solver/sundials_library.hpp"

namespace phasmid::app {
std::vector<Verb>& verbs() {
  static std::vector<Verb> v;
  return v;
}
static std::string g_command_line;
const std::string& command_line() { return g_command_line; }
}  // namespace phasmid::app

namespace {
// Under mpirun every rank runs the verb; rank 0 reports errors, other ranks name themselves.
std::string error_prefix() {
  const int r = phasmid::dist::rank();
  return r == 0 ? "phasmid: " : "phasmid (rank " + std::to_string(r) + "): ";
}

// Errors are one line of text (docs/cli.md) even when they quote input with line breaks or
// other control characters in it.
std::string one_line(std::string s) {
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';
  return s;
}

// A rank that fails while others may wait for it ends the whole MPI job.
int failed(int code) {
  std::cerr.flush();
  if (phasmid::dist::size() > 1 && !phasmid::dist::workers_released()) phasmid::dist::abort_job(code);
  return code;
}
}  // namespace

int main(int argc, char** argv) {
  using namespace phasmid::app;
  phasmid::dist::Session mpi(argc, argv);
  for (int i = 0; i < argc; ++i) g_command_line += (i ? " " : "") + std::string(argv[i]);

  CLI::App app{"phasmid: simulation, sensitivities, fits and sweeps of the stick-insect walking model"};
  app.set_version_flag("--version", std::string(PHASMID_VERSION) + " (" + phasmid::dist::mpi_description() + "; " +
                                         phasmid::solver::sundials_description() + ")");
  app.require_subcommand(1);
  // Usage errors in one line, like every other error (docs/cli.md).
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "phasmid: error: " + one_line(e.what()) + " (see phasmid --help)\n";
  });
  std::function<int()> action;
  for (auto& verb : verbs()) {
    CLI::App* sub = app.add_subcommand(verb.name, verb.description);
    auto run = verb.setup(*sub);
    sub->callback([&action, run] { action = run; });
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  const std::string verb = app.get_subcommands().empty() ? "" : app.get_subcommands().front()->get_name();
  if (phasmid::dist::size() > 1 && verb != "sweep" && verb != "fit" && verb != "gsa") {  // every rank would write the same file
    if (phasmid::dist::rank() == 0)
      std::cerr << "phasmid: error: phasmid " << verb << " runs in one process; under mpirun only sweep, fit and gsa use "
                << "several ranks (docs/cluster.md)\n";
    return 1;
  }
  try {
    return action ? action() : 1;
  } catch (const phasmid::Error& e) {
    std::cerr << error_prefix() << "error: " << one_line(e.what()) << "\n";
    return failed(1);
  } catch (const std::exception& e) {
    std::cerr << error_prefix() << "internal error: " << one_line(e.what()) << "\n";
    return failed(2);
  }
}
