#include "fit/condition_problem.hpp"

#include <algorithm>
#include <set>

#include "common/error.hpp"
#include "io/h5_file.hpp"

namespace phasmid::fit {
namespace {

// The conditions the targets use, in order: "" (the model as configured) first if any target
// has none, then the recordings' in the order they appear.
std::vector<std::string> used_conditions(const Targets& t) {
  std::vector<std::string> ids;
  const bool plain = !t.features.empty() || !t.switches.empty() || !t.kinematics.empty() ||
                     std::any_of(t.step_cycles.begin(), t.step_cycles.end(), [](auto& s) { return s.condition.empty(); });
  if (plain) ids.push_back("");
  for (const auto& s : t.step_cycles)
    if (!s.condition.empty() && std::find(ids.begin(), ids.end(), s.condition) == ids.end()) ids.push_back(s.condition);
  return ids;
}

Targets targets_of(const Targets& all, const std::string& id) {
  Targets t;
  if (id.empty()) t.features = all.features, t.switches = all.switches, t.kinematics = all.kinematics;
  for (const auto& s : all.step_cycles)
    if (s.condition == id) t.step_cycles.push_back(s);
  return t;
}

// The unit of a model parameter, or of the first that a pattern matches.
std::string unit_of(const model::OdeModel& model, const std::string& name) {
  const auto& ps = model.parameters();
  for (size_t k = 0; k < ps.size(); ++k)
    if (ps.at(k).name == name || (is_parameter_pattern(name) && parameter_id_matches(name, ps.at(k).name))) return ps.at(k).unit;
  return "";
}

// The parameters targets name that are not the model's: time offsets, observables' offsets,
// scales and noises.
std::set<std::string> target_parameters(const Targets& t) {
  std::set<std::string> ids;
  for (const auto& k : t.kinematics) ids.insert(k.time_offset_parameter);
  for (const auto& s : t.step_cycles)
    for (const auto& o : s.observables) ids.insert({o.offset_parameter, o.scale_parameter, o.sigma_parameter});
  ids.erase("");
  return ids;
}

const FitParameter& find_parameter(const std::vector<FitParameter>& ps, const std::string& id) {
  return *std::find_if(ps.begin(), ps.end(), [&](const FitParameter& p) { return p.id == id; });
}

// Every target's condition defined, every condition used, every mapped fit parameter in the
// table and not itself a model parameter.
void check_conditions(const model::OdeModel& model, const std::vector<FitParameter>& parameters, const Targets& targets,
                      const std::vector<Condition>& conditions, const std::vector<std::string>& used) {
  for (const auto& s : targets.step_cycles)
    if (!s.condition.empty() &&
        std::none_of(conditions.begin(), conditions.end(), [&](const Condition& c) { return c.id == s.condition; }))
      throw Error(s.origin + ": condition '" + s.condition + "' is not defined (give [fit.conditions." + s.condition + "])");
  for (const auto& c : conditions) {
    if (std::find(used.begin(), used.end(), c.id) == used.end())
      throw Error(c.origin + ": condition '" + c.id + "' has no targets (give a [[fit.recording]] condition = \"" + c.id + "\")");
    for (const auto& mapped : c.parameter_ids) {
      const std::string &name = mapped.first, &pid = mapped.second;
      if (std::none_of(parameters.begin(), parameters.end(), [&](const FitParameter& p) { return p.id == pid; }))
        throw Error(c.origin + ": condition '" + c.id + "' sets '" + name + "' to '" + pid + "', which is not in [fit.parameters]");
      if (model.parameters().contains(pid))
        throw Error(c.origin + ": condition '" + c.id + "' sets '" + name + "' to '" + pid +
                    "', a model parameter; give the condition's parameter a name of its own");
    }
  }
}

}  // namespace

ConditionsProblem::ConditionsProblem(const model::OdeModel& model, const std::vector<FitParameter>& parameters,
                                     const Targets& targets, const ProblemSettings& settings,
                                     const std::vector<Condition>& conditions) {
  const std::vector<std::string> used = used_conditions(targets);
  check_conditions(model, parameters, targets, conditions, used);
  std::set<std::string> condition_ids;  // fit parameters that some condition maps
  for (const auto& c : conditions)
    for (const auto& kv : c.parameter_ids) condition_ids.insert(kv.second);
  params_ = parameters;
  for (const auto& p : parameters)
    if (p.estimate) est_.push_back(p);
  size_t step_base = 0;
  std::set<size_t> used_columns;
  for (const std::string& id : used) {
    static const Condition none;
    const auto ci = std::find_if(conditions.begin(), conditions.end(), [&](const Condition& c) { return c.id == id; });
    const Condition& cond = ci == conditions.end() ? none : *ci;
    Part part;
    part.id = id;
    Targets t = targets_of(targets, id);
    const std::set<std::string> referenced = target_parameters(t);
    // The shared parameters, less those the condition sets and the targets' own (offsets,
    // scales, noises) that its targets do not use; then the condition's.
    std::vector<FitParameter> ps;
    std::vector<std::string> global;  // per entry of ps: its id in `parameters`
    for (const auto& p : parameters) {
      const bool of_model = model.parameters().contains(p.id) || is_parameter_pattern(p.id);
      if (!condition_ids.count(p.id) && !cond.parameter_ids.count(p.id) && !cond.values.count(p.id) &&
          (of_model || referenced.count(p.id)))
        ps.push_back(p), global.push_back(p.id);
    }
    for (const auto& [name, pid] : cond.parameter_ids) {
      FitParameter q = find_parameter(parameters, pid);
      q.id = name;
      ps.push_back(q), global.push_back(pid);
      part.mapped.push_back(name), part.fit_ids.push_back(pid), part.fixed.push_back(q.nominal);
    }
    for (const auto& [name, value] : cond.values) {
      ps.push_back({name, Scale::Lin, value, value, value, false, cond.origin, {}}), global.push_back("");
      part.mapped.push_back(name), part.fit_ids.push_back(""), part.fixed.push_back(value);
    }
    ProblemSettings s = settings;
    s.condition = id;
    s.step_output_base = step_base;
    step_base += t.step_cycles.size();
    try {
      part.problem = std::make_unique<FitProblem>(model, ps, std::move(t), s);
    } catch (const Error& e) {
      throw Error(id.empty() ? e.what() : "condition '" + id + "': " + e.what());
    }
    for (size_t g = 0; g < ps.size(); ++g) {
      if (!ps[g].estimate) continue;
      const auto it = std::find_if(est_.begin(), est_.end(), [&](const FitParameter& p) { return p.id == global[g]; });
      part.columns.push_back(static_cast<size_t>(it - est_.begin()));
    }
    part.first_row = labels_.size();
    for (size_t j : part.columns) used_columns.insert(j);
    for (const auto& l : part.problem->residual_labels()) labels_.push_back(id.empty() ? l : "[" + id + "] " + l);
    parts_.push_back(std::move(part));
  }
  for (size_t j = 0; j < est_.size(); ++j)
    if (!used_columns.count(j))
      throw Error((est_[j].origin.empty() ? "" : est_[j].origin + ": ") + "parameter '" + est_[j].id +
                  "' is estimated but no condition uses it (every condition sets it, or no target names it)");
}

std::vector<double> ConditionsProblem::part_x(const Part& p, const double* x) const {
  std::vector<double> xc;
  for (size_t j : p.columns) xc.push_back(x[j]);
  return xc;
}

std::string ConditionsProblem::parameter_unit(size_t j) const {
  for (const auto& p : parts_)
    for (size_t k = 0; k < p.columns.size(); ++k)
      if (p.columns[k] == j) return p.problem->parameter_unit(k);
  return "";
}

std::vector<std::string> ConditionsProblem::tied_parameters(size_t j) const {
  std::vector<std::string> names;
  for (const auto& p : parts_)
    for (size_t k = 0; k < p.columns.size(); ++k)
      if (p.columns[k] == j)
        for (const auto& n : p.problem->tied_parameters(k))
          if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
  return names;
}

bool ConditionsProblem::has_jacobian() const {
  return std::all_of(parts_.begin(), parts_.end(), [](const Part& p) { return p.problem->has_jacobian(); });
}

std::string ConditionsProblem::no_jacobian_reason() const {
  for (const auto& p : parts_)
    if (!p.problem->has_jacobian()) return p.problem->no_jacobian_reason();
  return "";
}

bool ConditionsProblem::evaluate(const double* x, double* r, double* J, std::string* error) const {
  const size_t n = est_.size();
  if (J) std::fill(J, J + labels_.size() * n, 0.0);
  std::vector<std::string> errors(parts_.size());
  std::vector<char> ok(parts_.size(), 1);
#pragma omp parallel for schedule(dynamic) if (parts_.size() > 1)
  for (long c = 0; c < static_cast<long>(parts_.size()); ++c) {
    const Part& p = parts_[static_cast<size_t>(c)];
    const std::vector<double> xc = part_x(p, x);
    const size_t mc = p.problem->num_residuals(), nc = xc.size();
    std::vector<double> Jc(J ? mc * nc : 0);
    ok[c] = p.problem->evaluate(xc.data(), r + p.first_row, J ? Jc.data() : nullptr, &errors[c]);
    if (!ok[c] || !J) continue;
    for (size_t q = 0; q < mc; ++q)
      for (size_t k = 0; k < nc; ++k) J[(p.first_row + q) * n + p.columns[k]] = Jc[q * nc + k];
  }
  for (size_t c = 0; c < parts_.size(); ++c)
    if (!ok[c]) {
      if (error) *error = parts_[c].id.empty() ? errors[c] : "condition '" + parts_[c].id + "': " + errors[c];
      return false;
    }
  return true;
}

void ConditionsProblem::write_model_output(io::H5Writer& out, const double* x, bool usable, double output_dt_ms) const {
  for (size_t c = 0; c < parts_.size(); ++c) {
    const Part& p = parts_[c];
    const std::vector<double> xc = part_x(p, x);
    if (c == 0) p.problem->write_model_output(out, xc.data(), usable, output_dt_ms);
    else if (usable) p.problem->write_step_comparison(out, xc.data());
    if (p.id.empty()) continue;
    std::vector<double> values = p.fixed;
    for (size_t k = 0; k < p.mapped.size(); ++k) {
      const auto e = std::find_if(est_.begin(), est_.end(), [&](const FitParameter& q) { return q.id == p.fit_ids[k]; });
      if (!p.fit_ids[k].empty() && e != est_.end()) values[k] = from_scaled(e->scale, x[e - est_.begin()]);
    }
    for (size_t k = 0; k < p.mapped.size(); ++k) {
      const std::string d = "/fit/conditions/" + p.id + "/" + p.mapped[k];
      out.write_scalar(d, values[k], unit_of(p.problem->model(), p.mapped[k]));
      if (!p.fit_ids[k].empty()) out.set_attribute(d, "fit_parameter", p.fit_ids[k]);
    }
  }
}

}  // namespace phasmid::fit
