#include "continuation/sensitivity_job.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/error.hpp"
#include "features/features.hpp"

namespace phasmid::sensitivity {

Mode parse_mode(const std::string& s) {
  if (s == "auto") return Mode::Auto;
  if (s == "steady_cycle") return Mode::SteadyCycle;
  if (s == "transient") return Mode::Transient;
  throw Error("unknown sensitivity mode '" + s + "' (expected auto, steady_cycle or transient)");
}

const char* mode_name(Mode m) {
  return m == Mode::Auto ? "auto" : m == Mode::SteadyCycle ? "steady_cycle" : "transient";
}

namespace {

// The steady-cycle analysis with the job's section, transient and period window.
continuation::CycleSensitivity cycle_sensitivities(const model::OdeModel& model, const std::vector<double>& p,
                                                   const SensitivityJob& job) {
  continuation::CycleSensitivityOptions co = job.cycle;
  if (job.section_from_model) co.shooting.section = default_section(model);
  co.shooting.transient_ms = job.floquet_options.transient_ms;
  co.shooting.max_period_ms = job.floquet_options.max_period_ms;
  return continuation::analyse_cycle_sensitivities(model, p, job.options, co);
}

}  // namespace

SensitivityOutcome run_sensitivity_job(const model::OdeModel& model, const std::vector<double>& p,
                                       const SensitivityJob& job, const std::function<void(const std::string&)>& on_note) {
  SensitivityOutcome out;
  if (job.mode != Mode::Transient) {
    try {
      out.cycle = cycle_sensitivities(model, p, job);
      out.report = std::move(out.cycle.report);
      out.cycle.report = {};
      out.has_cycle = true;
      out.mode = Mode::SteadyCycle;
    } catch (const continuation::NoSteadyCycle& e) {
      if (job.mode == Mode::SteadyCycle) throw;
      out.note = std::string(e.what()) + "; differentiating the transient run instead";
      if (on_note) on_note(out.note);
    }
  }
  if (!out.has_cycle) out.report = analyse_sensitivities(model, p, job.options);
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
  w.set_attribute("/sensitivity", "mode", std::string(mode_name(outcome.mode)));
  if (!outcome.note.empty()) w.set_attribute("/sensitivity", "mode_note", outcome.note);
  if (outcome.has_cycle) continuation::write_cycle_h5(w, model, outcome.cycle);
  if (outcome.has_floquet) write_floquet_h5(w, model, outcome.floquet);
  if (outcome.has_prc) write_prc_h5(w, model, job.prc_options, outcome.prc);
  w.commit();
}

std::string format_summary(const SensitivityOutcome& o, size_t top) {
  const auto& r = o.report;
  std::ostringstream os;
  char buf[512];
  std::snprintf(buf, sizeof buf, "sensitivity (%s, %s) of %zu features to %zu parameters in %.2f s\n",
                mode_name(o.mode), method_name(r.method), r.features.size(), r.parameters.size(), r.wall_seconds);
  os << buf;
  if (o.has_cycle) {
    std::snprintf(buf, sizeof buf, "  steady cycle: period %.6g ms, residual %.2g after %d Newton iterations, section %s\n",
                  o.cycle.cycle.period_ms, o.cycle.residual, o.cycle.newton.iterations, o.cycle.section.c_str());
    os << buf;
  }
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
