#include "output/run_file.hpp"

#include <utility>

namespace phasmid::output {
namespace {
std::string& command_text() {
  static std::string text;
  return text;
}
}  // namespace

void set_command_line(std::string text) { command_text() = std::move(text); }
const std::string& command_line() { return command_text(); }

void write_run_file(io::H5Writer& w, const config::Config& cfg, const std::vector<std::string>& sets,
                    const scenario::Scenario& scenario) {
  w.write_run_info({config::resolved_config_text(cfg, sets), command_line()});
  w.set_attribute("/", "model", scenario.kind());
}

}  // namespace phasmid::output
