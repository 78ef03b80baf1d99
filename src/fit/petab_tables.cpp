#include "fit/petab_tables.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "common/error.hpp"
#include "fit/text_table.hpp"

namespace phasmid::fit {
namespace {

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::string id_of(const std::string& name) {
  std::string s = name;
  std::replace(s.begin(), s.end(), '.', '_');
  return s;
}


size_t channel_index(const StepCycleTarget& t, const Observable& o) {
  const auto it = std::find(t.data.channels.begin(), t.data.channels.end(), o.data_channel);
  if (it == t.data.channels.end()) throw Error(o.origin + ": the recording has no channel '" + o.data_channel + "'");
  return static_cast<size_t>(it - t.data.channels.begin());
}

// Observable ids: the data channel's, with the condition (or the recording's index) appended
// when several recordings share a leg.
std::string observable_suffix(const Targets& targets, size_t i) {
  const auto& t = targets.step_cycles[i];
  const auto same_leg = std::count_if(targets.step_cycles.begin(), targets.step_cycles.end(),
                                      [&](const StepCycleTarget& u) { return u.leg == t.leg; });
  if (same_leg < 2) return "";
  return "_" + (t.condition.empty() ? std::to_string(i) : t.condition);
}

std::string condition_id(const StepCycleTarget& t) { return t.condition.empty() ? "model" : t.condition; }

void check_recordings_only(const Targets& targets) {
  if (!targets.features.empty()) throw Error(targets.features[0].origin + ": PEtab tables hold recordings ([[fit.recording]]) only, not feature targets");
  if (!targets.switches.empty()) throw Error(targets.switches[0].origin + ": PEtab tables hold recordings ([[fit.recording]]) only, not switch conditions");
  if (!targets.kinematics.empty()) throw Error(targets.kinematics[0].origin + ": PEtab tables hold recordings ([[fit.recording]]) only, not [fit.data]");
  if (targets.step_cycles.empty()) throw Error("PEtab tables: the fit has no [[fit.recording]]");
}

std::string conditions_table(const Targets& targets, const std::vector<Condition>& conditions) {
  std::set<std::string> columns;
  for (const auto& c : conditions) {
    for (const auto& kv : c.parameter_ids) columns.insert(kv.first);
    for (const auto& kv : c.values) columns.insert(kv.first);
  }
  std::ostringstream os;
  os << "conditionId";
  for (const auto& c : columns) os << '\t' << c;
  os << '\n';
  std::vector<std::string> ids;
  for (const auto& t : targets.step_cycles)
    if (std::find(ids.begin(), ids.end(), condition_id(t)) == ids.end()) ids.push_back(condition_id(t));
  for (const auto& id : ids) {
    os << id;
    const auto c = std::find_if(conditions.begin(), conditions.end(), [&](const Condition& k) { return k.id == id; });
    for (const auto& col : columns) {
      os << '\t';
      if (c == conditions.end()) continue;
      if (c->parameter_ids.count(col)) os << c->parameter_ids.at(col);
      else if (c->values.count(col)) os << num(c->values.at(col));
    }
    os << '\n';
  }
  return os.str();
}

}  // namespace

PetabTables format_petab(const Targets& targets, const std::vector<Condition>& conditions) {
  check_recordings_only(targets);
  std::ostringstream obs, meas;
  obs << "observableId\tobservableName\tobservableFormula\tnoiseFormula\tobservableTransformation\tnoiseDistribution\n";
  meas << "observableId\tsimulationConditionId\tmeasurement\ttime\tnoiseParameters\n";
  for (size_t i = 0; i < targets.step_cycles.size(); ++i) {
    const StepCycleTarget& t = targets.step_cycles[i];
    const std::string suffix = observable_suffix(targets, i), cond = condition_id(t);
    for (const Observable& o : t.observables) {
      const std::string id = id_of(o.data_channel) + suffix;
      const bool per_bin = o.sigma_parameter.empty() && !(o.sigma_deg > 0);
      obs << id << '\t' << o.data_channel << '\t' << num(o.sign) << " * "
          << (o.scale_parameter.empty() ? num(o.scale) : o.scale_parameter) << " * " << o.model_channel << " + "
          << (o.offset_parameter.empty() ? num(o.offset_deg) : o.offset_parameter) << '\t'
          << (!o.sigma_parameter.empty() ? o.sigma_parameter : per_bin ? kPetabNoisePlaceholder + id : num(o.sigma_deg))
          << "\tlin\tnormal\n";
      const size_t c = channel_index(t, o);
      for (size_t k = 0; k < t.data.phase.size(); ++k)
        meas << id << '\t' << cond << '\t' << num(t.data.mean_deg[c][k]) << '\t'
             << num(t.data.phase[k] * t.data.mean_period_ms) << '\t'
             << (per_bin ? num(t.bin_sd_deg(c, k)) : "") << '\n';
    }
    for (const char* what : {"period", "duty_factor"}) {
      const bool period = what[0] == 'p';
      const std::string id = t.leg + "_" + what + suffix;
      obs << id << '\t' << t.leg << '.' << what << '\t' << (period ? "period_ms(" : "duty_factor(") << t.model_leg << ")\t"
          << kPetabNoisePlaceholder << id << "\tlin\tnormal\n";
      meas << id << '\t' << cond << '\t' << num(period ? t.data.mean_period_ms : t.data.duty_factor) << "\tinf\t"
           << num(period ? t.period_noise_ms() : t.duty_factor_noise()) << '\n';
    }
  }
  return {obs.str(), meas.str(), conditions_table(targets, conditions)};
}

}  // namespace phasmid::fit
