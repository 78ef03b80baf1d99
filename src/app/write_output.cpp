#include "app/write_output.hpp"

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "parallel/executor.hpp"
#include "parallel/session.hpp"

namespace phasmid::app {

std::unique_ptr<io::OutputLock> lock_output(const std::string& out, bool release_workers) {
  if (parallel::rank() != 0) return nullptr;
  try {
    return std::make_unique<io::OutputLock>(out);
  } catch (...) {
    if (release_workers) parallel::release_workers();
    throw;
  }
}

void print_features_json(const std::vector<features::Feature>& features) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& f : features)
    out.push_back({{"name", f.name}, {"value", std::isfinite(f.value) ? nlohmann::json(f.value) : nlohmann::json()},
                   {"unit", f.unit}});
  std::cout << out.dump(2) << "\n";
}

int report_unfinished_sweep(const std::string& verb, const sweep::SweepOutcome& r, const std::string& what,
                            const std::string& resume_command) {
  std::cerr << "phasmid " << verb << ": " << (r.signal ? "interrupted" : "stopped") << " with "
            << (r.n_recovered + r.n_computed) << " of " << r.n_points << " " << what << " done (kept in " << r.journal
            << "); continue with: " << (r.distributed ? "mpirun ... " : "") << resume_command << " --resume\n";
  return r.signal ? 128 + r.signal : 3;
}

}  // namespace phasmid::app
