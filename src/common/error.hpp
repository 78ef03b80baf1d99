#pragma once
// One exception type for everything a user can get wrong or a solver can fail at.
// The CLI prints what() as a single line on stderr and exits non-zero.
#include <stdexcept>
#include <string>

namespace phasmid {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Numerical failure inside an integration or optimisation (kept apart so sweeps and fits
// can record it as the reason for a failed point instead of aborting).
class SolverError : public Error {
 public:
  explicit SolverError(const std::string& message) : Error(message) {}
};

}  // namespace phasmid
