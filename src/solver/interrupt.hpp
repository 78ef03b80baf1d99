#pragma once
// A process-wide request to stop the runs in progress (Ctrl-C in the Python module, which
// installs a SIGINT handler calling request_interrupt() while C++ runs; docs/python.md).
// Every integration loop checks it once per step (ProgressLine::update) and throws Interrupted,
// so a long run ends within one solver step and unwinds like any other error.
#include <string>

#include "common/error.hpp"

namespace phasmid::solver {

// Not a SolverError: sweeps and fits record those as failed points and go on.
class Interrupted : public Error {
 public:
  explicit Interrupted(const std::string& message) : Error(message) {}
};

void request_interrupt();  // async-signal-safe (sets a lock-free atomic flag)
void clear_interrupt();
bool interrupt_requested();

}  // namespace phasmid::solver
