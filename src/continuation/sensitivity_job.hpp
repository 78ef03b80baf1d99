#pragma once
// Everything `phasmid sensitivity CONFIG [-o OUT.h5] [--method forward|fd]` does once the
// model is assembled: the options of the config's [sensitivity] section, the analysis (of the
// steady cycle or of the run's transient), the optional limit-cycle analyses, and the HDF5 file
// (docs/hdf5.md, docs/sensitivity.md). It lives with the continuation code because the
// steady-cycle mode finds its cycle by Newton shooting.
#include <functional>
#include <string>
#include <vector>


#include "io/h5_file.hpp"
#include "continuation/cycle_sensitivity.hpp"
#include "sensitivity/floquet.hpp"
#include "sensitivity/sensitivity.hpp"

namespace phasmid::sensitivity {

// What is differentiated. SteadyCycle: the converged periodic orbit and the features on it
// (continuation/cycle_sensitivity.hpp). Transient: the features of the run's window
// [discard_ms, t_end_ms], for transient questions (a switch, a gait transition). Auto: the
// steady cycle where the orbit closes, else the transient with one line saying why.
enum class Mode { Auto, SteadyCycle, Transient };
Mode parse_mode(const std::string& s);  // "auto" | "steady_cycle" | "transient"; throws Error otherwise
const char* mode_name(Mode m);

struct SensitivityJob {
  Mode mode = Mode::Auto;
  SensitivityOptions options;
  continuation::CycleSensitivityOptions cycle;  // its section: the model's default unless set
  bool floquet = false;  // monodromy matrix and multipliers of the cycle
  FloquetOptions floquet_options;
  bool section_from_model = true;  // Poincare section at the first angle's maxima (default_section)
  bool prc = false;      // phase response curve
  PrcOptions prc_options;
};

struct SensitivityOutcome {
  Mode mode = Mode::Transient;  // the mode that ran (never Auto)
  std::string note;             // why Auto fell back to the transient (empty otherwise)
  SensitivityReport report;
  bool has_cycle = false;
  continuation::CycleSensitivity cycle;  // (report moved to `report`)
  bool has_floquet = false;
  FloquetResult floquet;
  bool has_prc = false;
  PhaseResponseCurve prc;
};

// `on_note` (may be empty) receives the one line of a fall-back from Auto to Transient.
SensitivityOutcome run_sensitivity_job(const model::OdeModel& model, const std::vector<double>& p,
                                       const SensitivityJob& job,
                                       const std::function<void(const std::string&)>& on_note = {});

// Writes run info, /parameters/{names,values,units}, /features, /sensitivity/... (and
// /sensitivity/floquet, /sensitivity/prc) to `path` atomically.
void write_sensitivity_file(const std::string& path, const model::OdeModel& model, const std::vector<double>& p,
                            const SensitivityJob& job, const SensitivityOutcome& outcome, const io::RunInfo& info);

// A human-readable summary: per feature its value and the `top` parameters by |relative|.
std::string format_summary(const SensitivityOutcome& outcome, size_t top = 3);

}  // namespace phasmid::sensitivity
