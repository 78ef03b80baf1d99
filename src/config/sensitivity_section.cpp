#include "config/sensitivity_section.hpp"

#include <cmath>

#include "common/error.hpp"

namespace phasmid::config {
using namespace sensitivity;

namespace {
using config::where;

double number(const toml::node& n, const std::string& key, const std::string& origin) {
  auto v = n.value<double>();
  if (!v || !std::isfinite(*v)) throw Error(where(origin, n) + ": [sensitivity] " + key + " must be a finite number");
  return *v;
}

bool boolean(const toml::node& n, const std::string& key, const std::string& origin) {
  if (auto v = n.value<bool>()) return *v;
  throw Error(where(origin, n) + ": [sensitivity] " + key + " must be true or false");
}

std::string text(const toml::node& n, const std::string& key, const std::string& origin) {
  if (auto v = n.value<std::string>()) return *v;
  throw Error(where(origin, n) + ": [sensitivity] " + key + " must be a string");
}

}  // namespace

SensitivityJob parse_sensitivity_section(const toml::table& section, const model::OdeModel& model,
                                         const std::string& origin, SensitivityJob job) {
  for (auto&& [k, node] : section) {
    const std::string key(k.str());
    const std::string at = where(origin, node);
    if (key == "parameters") {
      auto* arr = node.as_array();
      if (!arr) throw Error(at + ": [sensitivity] parameters must be a list of parameter names");
      // An empty list would silently mean every parameter (the default without the key).
      if (arr->empty()) throw Error(at + ": [sensitivity] parameters is empty; name at least one (leave the key out for all)");
      job.options.parameters.clear();
      for (auto& e : *arr) {
        std::string name = text(e, "parameters", origin);
        try {
          model.parameters().index(name);
        } catch (const Error& err) {
          throw Error(at + ": [sensitivity] " + err.what());
        }
        job.options.parameters.push_back(name);
      }
    } else if (key == "t_end_ms") {
      job.options.t_end_ms = number(node, key, origin);
    } else if (key == "output_dt_ms") {
      job.options.output_dt_ms = number(node, key, origin);
    } else if (key == "discard_ms") {
      job.options.discard_ms = number(node, key, origin);
    } else if (key == "method") {
      try {
        job.options.method = parse_method(text(node, key, origin));
      } catch (const Error& err) {
        throw Error(at + ": [sensitivity] " + err.what());
      }
    } else if (key == "mode") {
      try {
        job.mode = parse_mode(text(node, key, origin));
      } catch (const Error& err) {
        throw Error(at + ": [sensitivity] " + err.what());
      }
    } else if (key == "cycle_tolerance") {
      const double v = number(node, key, origin);
      if (!(v > 0)) throw Error(at + ": [sensitivity] cycle_tolerance must be a positive number (state units)");
      job.cycle.shooting.tolerance = v;
    } else if (key == "cycle_periods") {
      const double v = number(node, key, origin);
      if (!(v >= 2)) throw Error(at + ": [sensitivity] cycle_periods must be >= 2 (periods the features are computed on)");
      job.cycle.feature_cycles = v;
    } else if (key == "trajectory") {
      job.options.write_trajectory = boolean(node, key, origin);
    } else if (key == "fd_relative_step") {
      job.options.fd_relative_step = number(node, key, origin);
    } else if (key == "staggered") {
      job.options.solver.sensitivity_method =
          boolean(node, key, origin) ? solver::SensitivityMethod::Staggered : solver::SensitivityMethod::Simultaneous;
    } else if (key == "tolerance_factor") {
      const double v = number(node, key, origin);
      if (!(v > 0) || !std::isfinite(v)) throw Error(at + ": [sensitivity] tolerance_factor must be a positive number");
      job.options.solver.sensitivity_tolerance_factor = v;
    } else if (key == "floquet") {
      job.floquet = boolean(node, key, origin);
    } else if (key == "transient_ms") {
      job.floquet_options.transient_ms = number(node, key, origin);
    } else if (key == "max_period_ms") {
      job.floquet_options.max_period_ms = number(node, key, origin);
    } else if (key == "prc_state") {
      std::string s = text(node, key, origin);
      try {
        job.prc_options.state = model.state_index(s);
      } catch (const Error& err) {
        throw Error(at + ": [sensitivity] prc_state: " + err.what());
      }
      job.prc = true;
    } else if (key == "prc_amplitude") {
      job.prc_options.amplitude = number(node, key, origin);
    } else if (key == "prc_phases") {
      double v = number(node, key, origin);
      if (!(v >= 1)) throw Error(at + ": [sensitivity] prc_phases must be >= 1");
      job.prc_options.n_phases = static_cast<size_t>(v);
    } else if (key == "prc_cycles") {
      double v = number(node, key, origin);
      if (!(v >= 1)) throw Error(at + ": [sensitivity] prc_cycles must be >= 1");
      job.prc_options.cycles_after = static_cast<int>(v);
    } else {
      throw Error(at + ": [sensitivity] unknown key '" + key + "'");
    }
  }
  const auto& o = job.options;
  check_run_times(o.t_end_ms, o.output_dt_ms, o.discard_ms, origin + ": [sensitivity]");
  if (!(o.fd_relative_step > 0)) throw Error(origin + ": [sensitivity] fd_relative_step must be > 0");
  return job;
}

SensitivityJob sensitivity_job(const Config& cfg, const model::OdeModel& model, const SimulationSettings& sim) {
  const toml::table* section = cfg.table["sensitivity"].as_table();
  if (!section) throw Error(cfg.path + ": no [sensitivity] section (it lists the parameters to differentiate by)");
  SensitivityJob defaults;  // the run of [simulation], overridden by [sensitivity]
  defaults.options.t_end_ms = sim.t_end_ms;
  defaults.options.output_dt_ms = sim.output_dt_ms;
  defaults.options.discard_ms = sim.discard_ms;
  defaults.options.solver = sim.solver;
  return parse_sensitivity_section(*section, model, cfg.path, defaults);
}

}  // namespace phasmid::config
