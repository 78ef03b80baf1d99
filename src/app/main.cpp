// phasmid: one binary, many verbs (see docs/cli.md).
#include <CLI/CLI.hpp>
#include <iostream>

#include "app/verb.hpp"
#include "common/error.hpp"
#include "build_info.hpp"

namespace phasmid::app {
std::vector<Verb>& verbs() {
  static std::vector<Verb> v;
  return v;
}
static std::string g_command_line;
const std::string& command_line() { return g_command_line; }
}  // namespace phasmid::app

int main(int argc, char** argv) {
  using namespace phasmid::app;
  for (int i = 0; i < argc; ++i) g_command_line += (i ? " " : "") + std::string(argv[i]);

  CLI::App app{"phasmid: simulation, sensitivities, fits and sweeps of the stick-insect walking model"};
  app.set_version_flag("--version", PHASMID_VERSION);
  app.require_subcommand(1);
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
  try {
    return action ? action() : 1;
  } catch (const phasmid::Error& e) {
    std::cerr << "phasmid: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "phasmid: internal error: " << e.what() << "\n";
    return 2;
  }
}
