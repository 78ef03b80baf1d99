#pragma once
// Everything `phasmid sensitivity CONFIG [-o OUT.h5] [--method forward|fd]` does once the
// model is assembled: the options of the config's [sensitivity] section, the analysis, the
// optional limit-cycle analysis, and the HDF5 file (docs/hdf5.md, docs/sensitivity.md).
#include <string>
#include <vector>


#include "io/h5_file.hpp"
#include "sensitivity/floquet.hpp"
#include "sensitivity/sensitivity.hpp"

namespace phasmid::sensitivity {

struct SensitivityJob {
  SensitivityOptions options;
  bool floquet = false;  // monodromy matrix and multipliers of the cycle
  FloquetOptions floquet_options;
  bool section_from_model = true;  // Poincare section at the first angle's maxima (default_section)
  bool prc = false;      // phase response curve
  PrcOptions prc_options;
};

struct SensitivityOutcome {
  SensitivityReport report;
  bool has_floquet = false;
  FloquetResult floquet;
  bool has_prc = false;
  PhaseResponseCurve prc;
};

SensitivityOutcome run_sensitivity_job(const model::OdeModel& model, const std::vector<double>& p,
                                       const SensitivityJob& job);

// Writes run info, /parameters/{names,values,units}, /features, /sensitivity/... (and
// /sensitivity/floquet, /sensitivity/prc) to `path` atomically.
void write_sensitivity_file(const std::string& path, const model::OdeModel& model, const std::vector<double>& p,
                            const SensitivityJob& job, const SensitivityOutcome& outcome, const io::RunInfo& info);

// A human-readable summary: per feature its value and the `top` parameters by |relative|.
std::string format_summary(const SensitivityOutcome& outcome, size_t top = 3);

}  // namespace phasmid::sensitivity
