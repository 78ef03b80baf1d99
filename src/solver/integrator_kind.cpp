#include "solver/integrator_kind.hpp"

#include <utility>

namespace phasmid::solver {

namespace {
const std::pair<IntegratorKind, const char*> kNames[] = {{IntegratorKind::Bdf, "cvodes_bdf"},
                                                          {IntegratorKind::Dopri5, "dopri5"}};
}  // namespace

std::optional<IntegratorKind> integrator_from_name(const std::string& name) {
  for (const auto& [kind, n] : kNames)
    if (name == n) return kind;
  return std::nullopt;
}

std::string integrator_name(IntegratorKind kind) {
  for (const auto& [k, n] : kNames)
    if (k == kind) return n;
  return "unknown";
}

std::string integrator_names() {
  std::string s;
  for (const auto& [kind, n] : kNames) s += (s.empty() ? "\"" : ", \"") + std::string(n) + "\"";
  return s;
}

}  // namespace phasmid::solver
