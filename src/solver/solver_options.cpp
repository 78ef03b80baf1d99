#include "solver/solver_options.hpp"

#include <cmath>
#include <sstream>

#include "common/error.hpp"

namespace phasmid::solver {

namespace {

// "solver option 'NAME' must be WHAT, got VALUE" (the value as the user would write it).
template <class T>
std::string out_of_range(const char* name, const char* what, const T& value) {
  std::ostringstream os;
  os << "solver option '" << name << "' must be " << what << ", got " << value;
  return os.str();
}

bool in_open_unit_interval(double v) { return v > 0.0 && v < 1.0; }

// The per-unit tolerances of `name`: each unit named once, each value a tolerance in (0, 1).
bool check_by_unit(const char* name, const std::vector<std::pair<std::string, double>>& by_unit, std::string* error) {
  for (size_t i = 0; i < by_unit.size(); ++i) {
    const auto& [unit, value] = by_unit[i];
    if (!in_open_unit_interval(value)) {
      *error = out_of_range(name, "a list of tolerances in (0, 1)", value) + " for unit '" + unit + "'";
      return false;
    }
    for (size_t j = 0; j < i; ++j)
      if (by_unit[j].first == unit) {
        *error = std::string("solver option '") + name + "' names unit '" + unit + "' twice";
        return false;
      }
  }
  return true;
}

// The ranges of the single fields.
bool check_ranges(const SolverOptions& o, std::string* error) {
  if (!in_open_unit_interval(o.rtol)) *error = out_of_range("rtol", "in (0, 1)", o.rtol);
  else if (!in_open_unit_interval(o.atol)) *error = out_of_range("atol", "in (0, 1)", o.atol);
  else if (o.max_steps < 1) *error = out_of_range("max_steps", ">= 1", o.max_steps);
  else if (!(o.max_step_ms >= 0.0) || !std::isfinite(o.max_step_ms))
    *error = out_of_range("max_step_ms", ">= 0 (0: no limit)", o.max_step_ms);
  else if (!(o.sensitivity_tolerance_factor > 0.0) || !std::isfinite(o.sensitivity_tolerance_factor))
    *error = out_of_range("sensitivity_tolerance_factor", "> 0", o.sensitivity_tolerance_factor);
  else if (!in_open_unit_interval(o.stiff_part_tol)) *error = out_of_range("stiff_part_tol", "in (0, 1)", o.stiff_part_tol);
  else if (o.threads < 1 || o.threads > kMaxThreads)
    *error = out_of_range("threads", ("in 1.." + std::to_string(kMaxThreads)).c_str(), o.threads);
  else if (!(o.window_ms > 0.0) || !std::isfinite(o.window_ms)) *error = out_of_range("window_ms", "> 0", o.window_ms);
  else return check_by_unit("atol_by_unit", o.atol_by_unit, error) &&
              check_by_unit("stiff_part_atol_by_unit", o.stiff_part_atol_by_unit, error);
  return false;
}

// The combinations: a setting that would change nothing is refused rather than ignored.
bool check_combinations(const SolverOptions& o, std::string* error) {
  if (o.partitioning == Partitioning::Neurons && o.threads >= 2) {
    *error = std::string("solver option 'partitioning' = neurons runs on one thread (threads = 1, got ") +
             std::to_string(o.threads) + "): " + kNeuronsOnOneThread;
    return false;
  }
  if (!o.stiff_part_atol_by_unit.empty() && (o.partitioning != Partitioning::Neurons || !is_explicit_rk(o.integrator))) {
    *error = "solver option 'stiff_part_atol_by_unit' applies only with partitioning = neurons and an explicit "
             "integrator, whose network parts run CVODES BDF";
    return false;
  }
  return true;
}

}  // namespace

bool SolverOptions::is_valid(std::string* error) const {
  std::string local;
  std::string* e = error ? error : &local;
  return check_ranges(*this, e) && check_combinations(*this, e);
}

void SolverOptions::validate() const {
  std::string error;
  if (!is_valid(&error)) throw Error(error);
}

}  // namespace phasmid::solver
