// phasmid: one binary, many verbs (see docs/cli.md).
#include <CLI/CLI.hpp>
#include <iostream>

#include "app/verb.hpp"
#include "common/error.hpp"
#include "build_info.hpp"
#include "parallel/executor.hpp"
#include "parallel/session.hpp"
#include "solver/sundials_library.hpp"

namespace phasmid::app {
std::vector<Verb>& verbs() {
  static std::vector<Verb> v;
  return v;
}
}  // namespace phasmid::app

namespace {
// Under mpirun every rank runs the verb; rank 0 reports errors, other ranks name themselves.
std::string error_prefix(int r = phasmid::parallel::rank()) {
  return r == 0 ? "phasmid: " : "phasmid (rank " + std::to_string(r) + "): ";
}

// Errors are one line of text (docs/cli.md) even when they quote input with line breaks or
// other control characters in it.
std::string one_line(std::string s) {
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';
  return s;
}

// How a run ends (docs/cluster.md "Messages and exit status"). `line` is the error ("" if none).
// Without MPI: printed. Under MPI before any MPI work: the ranks agree, rank 0 prints the first
// failure and every rank ends normally. After it: the failing rank prints; rank 0 ends normally
// once it has released the workers, any other failure ends the whole job (MPI_Abort), since
// other ranks may be waiting for this one.
int finish(int code, const std::string& line) {
  namespace parallel = phasmid::parallel;
  if (parallel::size() > 1 && !parallel::agreed()) {
    const parallel::Agreement a = parallel::agree(line, code);
    if (parallel::rank() == 0 && !a.all_ok) std::cerr << error_prefix(a.failed_rank) << a.message << "\n";
    return a.all_ok ? code : a.code;
  }
  if (line.empty()) return code;
  std::cerr << error_prefix() << line << "\n";
  std::cerr.flush();
  if (parallel::size() > 1 && !(parallel::rank() == 0 && parallel::workers_released())) parallel::abort_job(code);
  return code;
}
}  // namespace

int main(int argc, char** argv) {
  using namespace phasmid::app;
  phasmid::parallel::Session mpi(argc, argv);
  std::string line;
  for (int i = 0; i < argc; ++i) line += (i ? " " : "") + std::string(argv[i]);
  phasmid::output::set_command_line(std::move(line));

  CLI::App app{"phasmid: simulation, sensitivities, fits and sweeps of the stick-insect walking model"};
  app.set_version_flag("--version", std::string(PHASMID_VERSION) + " (" + phasmid::parallel::mpi_description() + "; " +
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
    if (phasmid::parallel::rank() != 0) return e.get_exit_code();  // every rank parsed the same line: rank 0 says it
    return app.exit(e);
  }
  const std::string verb = app.get_subcommands().empty() ? "" : app.get_subcommands().front()->get_name();
  if (phasmid::parallel::size() > 1 && verb != "sweep" && verb != "fit" && verb != "gsa")  // every rank would write the same file
    return finish(1, "error: phasmid " + verb + " runs in one process; under mpirun only sweep, fit and gsa use "
                     "several ranks (docs/cluster.md)");
  try {
    return finish(action ? action() : 1, "");
  } catch (const phasmid::parallel::JobStopped& e) {  // another rank failed before any work
    if (phasmid::parallel::rank() == 0) std::cerr << error_prefix(e.failed_rank) << e.message << "\n";
    return e.code;
  } catch (const phasmid::Error& e) {
    return finish(1, "error: " + one_line(e.what()));
  } catch (const std::exception& e) {
    return finish(2, "internal error: " + one_line(e.what()));
  }
}
