#include "sensitivity/job.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/error.hpp"
#include "config/config.hpp"
#include "features/features.hpp"

namespace phasmid::sensitivity {
namespace {
using config::where;

double number(const toml::node& n, const std::string& key, const std::string& origin) {
  if (auto v = n.value<double>()) return *v;
  throw Error(where(origin, n) + ": [sensitivity] " + key + " must be a number");
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
  if (!(o.t_end_ms > 0) || !(o.output_dt_ms > 0) || o.discard_ms < 0 || o.discard_ms >= o.t_end_ms)
    throw Error(origin + ": [sensitivity] needs t_end_ms > 0, output_dt_ms > 0 and 0 <= discard_ms < t_end_ms");
  if (!(o.fd_relative_step > 0)) throw Error(origin + ": [sensitivity] fd_relative_step must be > 0");
  return job;
}

SensitivityOutcome run_sensitivity_job(const model::OdeModel& model, const std::vector<double>& p,
                                       const SensitivityJob& job) {
  SensitivityOutcome out;
  out.report = analyse_sensitivities(model, p, job.options);
  FloquetOptions fo = job.floquet_options;
  fo.solver = job.options.solver;
  if ((job.floquet || job.prc) && job.section_from_model) fo.section = default_section(model);
  if (job.floquet) {
    out.floquet = floquet_analysis(model, p, fo);
    out.has_floquet = true;
  }
  if (job.prc) {
    PrcOptions po = job.prc_options;
    po.floquet = fo;
    out.prc = phase_response_curve(model, p, po);
    out.has_prc = true;
  }
  return out;
}

void write_sensitivity_file(const std::string& path, const model::OdeModel& model, const std::vector<double>& p,
                            const SensitivityJob& job, const SensitivityOutcome& outcome, const io::RunInfo& info) {
  io::H5Writer w(path);
  w.write_run_info(info);
  std::vector<std::string> names, units;
  for (auto& par : model.parameters().all()) {
    names.push_back(par.name);
    units.push_back(par.unit);
  }
  w.write("/parameters/names", names);
  w.write("/parameters/units", units);
  w.write("/parameters/values", p, "see /parameters/units");
  features::write_features_h5(w, outcome.report.features);
  write_sensitivity_h5(w, outcome.report);
  if (outcome.has_floquet) write_floquet_h5(w, model, outcome.floquet);
  if (outcome.has_prc) write_prc_h5(w, model, job.prc_options, outcome.prc);
  w.commit();
}

std::string format_summary(const SensitivityOutcome& o, size_t top) {
  const auto& r = o.report;
  std::ostringstream os;
  char buf[512];
  std::snprintf(buf, sizeof buf, "sensitivity (%s) of %zu features to %zu parameters in %.2f s\n", method_name(r.method),
                r.features.size(), r.parameters.size(), r.wall_seconds);
  os << buf;
  for (size_t f = 0; f < r.features.size(); ++f) {
    std::snprintf(buf, sizeof buf, "  %-36s %12.6g %-4s", r.features[f].name.c_str(), r.features[f].value,
                  r.features[f].unit.c_str());
    os << buf;
    for (size_t k = 0; k < std::min(top, r.ranking[f].size()); ++k) {
      size_t j = 0;
      while (r.parameters[j] != r.ranking[f][k]) ++j;
      std::snprintf(buf, sizeof buf, "  %s %+.3g", r.parameters[j].c_str(), r.relative(f, j));
      os << buf;
    }
    os << "\n";
  }
  if (o.has_floquet) {
    std::snprintf(buf, sizeof buf, "  Floquet multipliers (period %.3f ms):", o.floquet.orbit.period_ms);
    os << buf;
    for (auto& m : o.floquet.multipliers) {
      std::snprintf(buf, sizeof buf, " %.4g%+.4gi", m.real(), m.imag());
      os << buf;
    }
    os << "\n";
  }
  return os.str();
}

}  // namespace phasmid::sensitivity
