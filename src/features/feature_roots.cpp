#include "common/units.hpp"
#include "features/feature_parts.hpp"

namespace phasmid::features {

namespace detail {

std::vector<LegRoot> leg_roots(const model::OdeModel& model, const std::vector<double>& p) {
  std::vector<LegRoot> out;
  auto value = [&](size_t k) { return p.empty() ? model.parameters().at(k).value : p.at(k); };
  for (const model::ContactLeg& l : model.structure().contact_legs) {
    LegRoot r{l.leg, l.beta_state, value(l.threshold_param)};
    if (l.retractor_state) {
      r.retractor_state = *l.retractor_state;
      r.retractor_level_mV = value(l.retractor_level_param);
    }
    out.push_back(r);
  }
  return out;
}

}  // namespace detail

std::vector<solver::RootSpec> feature_roots(const model::OdeModel& model) { return feature_roots(model, {}); }

std::vector<solver::RootSpec> feature_roots(const model::OdeModel& model, const std::vector<double>& p) {
  std::vector<solver::RootSpec> roots;
  for (const auto& ch : model.angles()) roots.push_back({ch.velocity_state, 0.0, 0});
  const std::vector<detail::LegRoot> legs = detail::leg_roots(model, p);
  for (const auto& l : legs) roots.push_back({l.beta_state, units::deg_to_rad(l.threshold_deg), 0});
  for (const auto& l : legs)
    if (l.retractor_state != detail::kNoState) roots.push_back({l.retractor_state, l.retractor_level_mV, 0});
  return roots;
}

}  // namespace phasmid::features
