#include "config/simroach2_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <map>
#include <toml++/toml.h>

#include "common/error.hpp"

namespace phasmid::config {
namespace {

// Assigns the numeric keys of `table` through `fields`; anything else is an error.
using Setter = std::function<void(double)>;
void assign(const toml::table& table, const std::string& where, const std::string& origin,
            const std::map<std::string, Setter>& fields, const std::vector<std::string>& handled = {}) {
  for (const auto& [key, node] : table) {
    const std::string k(key.str());
    if (std::find(handled.begin(), handled.end(), k) != handled.end()) continue;
    const auto line = node.source().begin.line;
    auto it = fields.find(k);
    if (it == fields.end()) throw Error(fmt::format("{}:{}: unknown key '{}.{}'", origin, line, where, k));
    auto v = node.value<double>();
    if (!v) throw Error(fmt::format("{}:{}: '{}.{}' must be a number", origin, line, where, k));
    it->second(*v);
  }
}

const toml::table& as_table(const toml::node& node, const std::string& where, const std::string& origin) {
  const auto* t = node.as_table();
  if (!t) throw Error(fmt::format("{}:{}: '{}' must be a table", origin, node.source().begin.line, where));
  return *t;
}

std::string required_string(const toml::table& t, const std::string& key, const std::string& where,
                            const std::string& origin) {
  auto v = t[key].value<std::string>();
  if (!v) throw Error(fmt::format("{}:{}: '{}' needs string key '{}'", origin, t.source().begin.line, where, key));
  return *v;
}

}  // namespace

simroach2::Components parse_simroach2_components(const std::string& text, const std::string& origin) {
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    throw Error(fmt::format("{}:{}: {}", origin, e.source().begin.line, e.description()));
  }
  simroach2::Components out;
  const auto* section = root["simroach2"].as_table();
  if (!section) return out;
  for (const auto& [kind_key, kind_node] : *section) {
    const std::string kind(kind_key.str());
    const auto& group = as_table(kind_node, "simroach2." + kind, origin);
    for (const auto& [name_key, node] : group) {
      const std::string name(name_key.str()), where = "simroach2." + kind + "." + name;
      const auto& t = as_table(node, where, origin);
      if (kind == "neuron") {
        simroach2::NeuronParameters& n = out.neurons[name];
        auto gate = [&](simroach2::GateSigmoid& g, const char* gate_name) {
          if (const auto* sub = t[gate_name].as_table())
            assign(*sub, where + "." + gate_name, origin,
                   {{"A", [&](double v) { g.A = v; }}, {"S", [&](double v) { g.S = v; }}, {"E", [&](double v) { g.E = v; }}});
        };
        gate(n.m, "m");
        gate(n.h, "h");
        assign(t, where, origin,
               {{"time_constant_ms", [&](double v) { n.time_constant_ms = v; }},
                {"relative_size_uS", [&](double v) { n.relative_size_uS = v; }},
                {"rest_potential_mV", [&](double v) { n.rest_potential_mV = v; }},
                {"g_na_uS", [&](double v) { n.g_na_uS = v; }},
                {"e_na_mV", [&](double v) { n.e_na_mV = v; }},
                {"tau_h_max_ms", [&](double v) { n.tau_h_max_ms = v; }}},
               {"m", "h"});
        if (!(n.time_constant_ms > 0 && n.relative_size_uS > 0))
          throw Error(fmt::format("{}:{}: {} needs positive time_constant_ms and relative_size_uS", origin,
                                  t.source().begin.line, where));
      } else if (kind == "synapse") {
        simroach2::SynapseParameters& s = out.synapses[name];
        assign(t, where, origin,
               {{"g_max_uS", [&](double v) { s.g_max_uS = v; }}, {"e_lo_mV", [&](double v) { s.e_lo_mV = v; }},
                {"e_hi_mV", [&](double v) { s.e_hi_mV = v; }}, {"e_rev_mV", [&](double v) { s.e_rev_mV = v; }}});
        if (s.e_hi_mV == s.e_lo_mV)
          throw Error(fmt::format("{}:{}: {}: e_hi_mV must differ from e_lo_mV", origin, t.source().begin.line, where));
      } else if (kind == "muscle") {
        const auto joint = required_string(t, "joint", where, origin);
        const auto muscle = required_string(t, "muscle", where, origin);
        simroach2::MuscleParameters& m = out.muscles[name] = simroach2::muscle_from_tables(joint, muscle);
        assign(t, where, origin,
               {{"k_se_N_per_m", [&](double v) { m.k_se_N_per_m = v; }},
                {"k_pe_N_per_m", [&](double v) { m.k_pe_N_per_m = v; }},
                {"b_Ns_per_m", [&](double v) { m.b_Ns_per_m = v; }},
                {"amplitude_N", [&](double v) { m.activation.amplitude_N = v; }},
                {"y_offset_mN", [&](double v) { m.activation.y_offset_mN = v; }},
                {"x_offset_mV", [&](double v) { m.activation.x_offset_mV = v; }},
                {"steepness_per_V", [&](double v) { m.activation.steepness_per_V = v; }},
                {"rest_length_mm", [&](double v) { m.rest_length_m = 1e-3 * v; }}},
               {"joint", "muscle"});
      } else if (kind == "joint") {
        const auto joint = required_string(t, "joint", where, origin);
        simroach2::PassiveSpringDamper& s = out.joints[name] = simroach2::spring_from_tables(joint);
        assign(t, where, origin,
               {{"stiffness_N_per_m", [&](double v) { s.stiffness_N_per_m = v; }},
                {"damping_mg_per_s", [&](double v) { s.damping_Ns_per_m = v * simroach2::kNsPerM_per_mgPerS; }},
                {"rest_length_mm", [&](double v) { s.rest_length_m = 1e-3 * v; }}},
               {"joint"});
      } else {
        throw Error(fmt::format("{}:{}: unknown component kind 'simroach2.{}' (neuron, synapse, muscle, joint)",
                                origin, kind_node.source().begin.line, kind));
      }
    }
  }
  return out;
}

}  // namespace phasmid::config
