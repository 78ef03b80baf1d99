#include "sensitivity/job.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/error.hpp"
#include "features/features.hpp"

namespace phasmid::sensitivity {

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
