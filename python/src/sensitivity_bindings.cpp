// phasmid._core.Sensitivity: forward sensitivities of a scenario (docs/python.md,
// docs/sensitivity.md). The matrices and trajectories are views of the C++ report.
#include <map>
#include <optional>

#include "bindings.hpp"
#include "config/sensitivity_section.hpp"
#include "io/output_path.hpp"
#include "continuation/sensitivity_job.hpp"

namespace phasmid::python {
namespace {

struct Sensitivity {
  std::shared_ptr<PyScenario> scenario;
  sensitivity::SensitivityJob job;
  std::vector<double> p;
  sensitivity::SensitivityOutcome outcome;

  void save(const std::string& path) const {
    io::check_output_path(path, scenario->inputs());
    const model::OdeModel& m = *scenario->scenario->ode_model();
    sensitivity::write_sensitivity_file(path, m, p, job, outcome,
                                        {config::resolved_config_text(scenario->cfg, scenario->sets), command_text()});
  }
};

struct SensitivityRequest {
  std::optional<std::vector<std::string>> parameters;
  std::optional<std::string> method;
  std::optional<double> t_end_ms, output_dt_ms, discard_ms;
  std::optional<bool> trajectory;
  std::optional<std::string> mode;
};

// The config's [sensitivity] job (or, without the section, the [simulation] run) with the
// keyword overrides of Scenario.sensitivity(), which go through the section's own parser
// (config::parse_sensitivity_section) as a table whose errors name "sensitivity()".
sensitivity::SensitivityJob make_job(const PyScenario& s, const model::OdeModel& m, const SensitivityRequest& r) {
  return config_stage([&] {
    sensitivity::SensitivityJob job;
    const config::SimulationSettings settings = config::bdf_simulation_settings(s.cfg, s.scenario.get());
    if (s.cfg.table["sensitivity"].as_table()) {
      job = config::sensitivity_job(s.cfg, m, settings);
    } else {
      job.options.t_end_ms = settings.t_end_ms;
      job.options.output_dt_ms = settings.output_dt_ms;
      job.options.discard_ms = settings.discard_ms;
      job.options.solver = settings.solver;
    }
    toml::table t;
    if (r.parameters) {
      toml::array names;
      for (const std::string& name : *r.parameters) names.push_back(name);
      t.insert("parameters", std::move(names));
    }
    if (r.method) t.insert("method", *r.method);
    if (r.t_end_ms) t.insert("t_end_ms", *r.t_end_ms);
    if (r.output_dt_ms) t.insert("output_dt_ms", *r.output_dt_ms);
    if (r.discard_ms) t.insert("discard_ms", *r.discard_ms);
    if (r.trajectory) t.insert("trajectory", *r.trajectory);
    if (r.mode) t.insert("mode", *r.mode);
    return config::parse_sensitivity_section(t, m, "sensitivity()", job);
  });
}

std::unique_ptr<Sensitivity> run(const std::shared_ptr<PyScenario>& s, const SensitivityRequest& r) {
  const model::OdeModel* m = s->scenario->ode_model();
  if (!m)
    throw ConfigError(s->cfg.path + ": model type " + s->scenario->kind() +
                      " is not an ODE system; forward sensitivities need one (use sweep or fit with a derivative-free optimizer)");
  auto out = std::make_unique<Sensitivity>();
  out->scenario = s;
  out->job = make_job(*s, *m, r);
  out->p = m->parameters().values();
  without_gil([&] { out->outcome = sensitivity::run_sensitivity_job(*m, out->p, out->job); });
  return out;
}

const sensitivity::SensitivityReport& report_of(py::handle self) { return self.cast<const Sensitivity&>().outcome.report; }

// features x parameters (Eigen stores it column-major).
py::array matrix_view(const Eigen::MatrixXd& a, py::handle self) {
  const auto d = static_cast<py::ssize_t>(sizeof(double));
  return view(a.data(), {a.rows(), a.cols()}, {d, d * a.rows()}, self);
}

void bind_arrays(py::class_<Sensitivity>& c) {
  c.def_property_readonly("absolute", [](py::object self) { return matrix_view(report_of(self).absolute, self); },
                          "features x parameters: dF/dp (feature unit per parameter unit)")
      .def_property_readonly("relative", [](py::object self) { return matrix_view(report_of(self).relative, self); },
                             "features x parameters: p/F dF/dp")
      .def_property_readonly("time", [](py::object self) { return view(report_of(self).time, self); })
      .def_property_readonly("trajectory", [](py::object self) {
        const auto& r = report_of(self);
        const auto d = static_cast<py::ssize_t>(sizeof(double));
        const auto T = static_cast<py::ssize_t>(r.time.size()), S = static_cast<py::ssize_t>(r.state_names.size()),
                   P = static_cast<py::ssize_t>(r.parameters.size());
        if (r.trajectory.empty()) return py::object(py::none());
        return py::object(view(r.trajectory.data(), {T, S, P}, {S * P * d, P * d, d}, self));
      }, "times x states x parameters: d state / d p (None when trajectory=False)")
      .def_property_readonly("states", [](py::object self) {
        const auto& r = report_of(self);
        const auto d = static_cast<py::ssize_t>(sizeof(double));
        const auto T = static_cast<py::ssize_t>(r.time.size()), S = static_cast<py::ssize_t>(r.state_names.size());
        if (r.states.empty()) return py::object(py::none());
        return py::object(view(r.states.data(), {T, S}, {S * d, d}, self));
      }, "times x states: the nominal trajectory");
}

void bind_labels(py::class_<Sensitivity>& c) {
  c.def_property_readonly("parameters", [](const Sensitivity& s) { return s.outcome.report.parameters; })
      .def_property_readonly("parameter_units", [](const Sensitivity& s) { return s.outcome.report.parameter_units; })
      .def_property_readonly("parameter_values", [](const Sensitivity& s) { return s.outcome.report.parameter_values; })
      .def_property_readonly("parameter_method", [](const Sensitivity& s) { return s.outcome.report.parameter_method; })
      .def_property_readonly("state_names", [](const Sensitivity& s) { return s.outcome.report.state_names; })
      .def_property_readonly("state_units", [](const Sensitivity& s) { return s.outcome.report.state_units; })
      .def_property_readonly("ranking", [](const Sensitivity& s) { return s.outcome.report.ranking; })
      .def_property_readonly("method", [](const Sensitivity& s) { return std::string(sensitivity::method_name(s.outcome.report.method)); })
      .def_property_readonly("mode", [](const Sensitivity& s) { return std::string(sensitivity::mode_name(s.outcome.mode)); })
      .def_property_readonly("mode_note", [](const Sensitivity& s) { return s.outcome.note; })
      .def_property_readonly("cycle_period_ms", [](const Sensitivity& s) {
        return s.outcome.has_cycle ? py::object(py::float_(s.outcome.cycle.cycle.period_ms)) : py::object(py::none());
      }, "period of the steady cycle (None in transient mode)")
      .def("feature_records", [](const Sensitivity& s) {
        py::list out;
        for (const auto& f : s.outcome.report.features) out.append(py::make_tuple(f.name, f.value, f.unit));
        return out;
      })
      .def("summary", [](const Sensitivity& s) { return sensitivity::format_summary(s.outcome); })
      .def("save", &Sensitivity::save, py::arg("path"));
}

}  // namespace

void bind_sensitivity(py::module_& m) {
  py::class_<Sensitivity> c(m, "Sensitivity", "Forward sensitivities (phasmid.SensitivityResult wraps it).");
  bind_arrays(c);
  bind_labels(c);
  m.def("sensitivity", [](const std::shared_ptr<PyScenario>& s, std::optional<std::vector<std::string>> parameters,
                          std::optional<std::string> method, std::optional<double> t_end_ms,
                          std::optional<double> output_dt_ms, std::optional<double> discard_ms,
                          std::optional<bool> trajectory, std::optional<std::string> mode) {
    return run(s, {parameters, method, t_end_ms, output_dt_ms, discard_ms, trajectory, mode});
  }, py::arg("scenario"), py::arg("parameters") = py::none(), py::arg("method") = py::none(),
        py::arg("t_end_ms") = py::none(), py::arg("output_dt_ms") = py::none(), py::arg("discard_ms") = py::none(),
        py::arg("trajectory") = py::none(), py::arg("mode") = py::none());
}

}  // namespace phasmid::python
