// phasmid._core.Scenario and phasmid._core.Simulation (docs/python.md).
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "output/run_file.hpp"
#include "bindings.hpp"
#include "common/units.hpp"
#include "config/simulation_table.hpp"
#include "io/h5_file.hpp"
#include "io/output_path.hpp"
#include "model/ode_model.hpp"

namespace phasmid::python {
namespace {

// One run of a scenario. Joint angles and angular velocities are converted to degrees once,
// here, by the expression the trajectory writer uses (so they equal the file's bit for bit).
struct Simulation {
  std::shared_ptr<PyScenario> scenario;
  std::unique_ptr<scenario::ScenarioRun> run;
  std::map<std::string, std::vector<double>> degrees;  // "angles/<leg>.<joint>", "angular_velocity/..."

  const solver::SolveResult& solution() const {
    if (!run->solution()) throw Error("model type " + scenario->scenario->kind() + " has no ODE trajectory; use .data");
    return *run->solution();
  }
  void convert_angles() {
    const model::OdeModel* m = scenario->scenario->ode_model();
    const solver::SolveResult* r = run->solution();
    if (!m || !r) return;
    const size_t n = r->t.size();
    for (const auto& a : m->angles()) {
      std::vector<double>& angle = degrees["angles/" + a.leg + "." + a.joint];
      std::vector<double>& velocity = degrees["angular_velocity/" + a.leg + "." + a.joint];
      angle.resize(n);
      velocity.resize(n);
      for (size_t k = 0; k < n; ++k) {
        angle[k] = units::rad_to_deg(r->state(k, a.angle_state));
        velocity[k] = units::rad_to_deg(r->state(k, a.velocity_state));
      }
    }
  }
  void save(const std::string& path) const {
    io::check_output_path(path, scenario->inputs());
    io::H5Writer w(path);
    output::write_run_file(w, scenario->cfg, scenario->sets, *scenario->scenario);
    run->write(w);
    w.commit();
  }
};

using Options = std::map<std::string, double>;

// [simulation] settings with the keyword overrides of simulate(): max_steps is the module's
// own; the others are read by the config's [simulation] code over the config's own request
// (config::read_simulation_table) and resolved by the model kind, as `phasmid simulate` does,
// with errors naming "simulate()" and the keyword.
scenario::RunSettings settings_with(const PyScenario& s, const Options& o) {
  static const std::set<std::string> keys = {"t_end_ms", "output_dt_ms", "discard_ms", "rtol", "atol", "max_step_ms"};
  toml::table table;
  std::optional<double> max_steps;
  for (const auto& [key, value] : o) {
    if (key == "max_steps") max_steps = value;
    else if (keys.count(key)) table.insert_or_assign(key, value);
    else
      throw ConfigError("simulate: unknown option '" + key +
                        "' (t_end_ms, output_dt_ms, discard_ms, rtol, atol, max_step_ms, max_steps)");
  }
  config::Config origin;
  origin.path = "simulate()";
  scenario::RunSettings r = s.settings;
  if (!table.empty())
    r = config_stage([&] {
      config::SimulationRequest request = config::simulation_request(s.cfg, s.scenario.get());
      request = config::read_simulation_table(origin, table, s.scenario.get(), request);
      return config::resolve_simulation(request, s.scenario.get(), origin.path);
    });
  if (max_steps) {
    if (!(*max_steps >= 1 && *max_steps <= 1e9) || *max_steps != std::floor(*max_steps))
      throw ConfigError("simulate(): 'max_steps' must be an integer in [1, 1e9] (solver steps per output interval)");
    r.solver.max_steps = static_cast<long>(*max_steps);
  }
  return r;
}

std::unique_ptr<Simulation> simulate(const std::shared_ptr<PyScenario>& s, const Options& o) {
  auto sim = std::make_unique<Simulation>();
  sim->scenario = s;
  const scenario::RunSettings settings = settings_with(*s, o);
  without_gil([&] {
    sim->run = s->scenario->run(s->scenario->parameters().values(), settings);
    sim->convert_angles();
  });
  return sim;
}

py::list parameter_records(const PyScenario& s) {
  py::list out;
  for (const auto& p : s.scenario->parameters().all())
    out.append(py::make_tuple(p.name, p.value, p.unit, p.source, p.description, p.lower, p.upper));
  return out;
}

py::list feature_records(const std::vector<features::Feature>& fs) {
  py::list out;
  for (const auto& f : fs) out.append(py::make_tuple(f.name, f.value, f.unit));
  return out;
}

void bind_scenario_class(py::module_& m) {
  py::class_<PyScenario, std::shared_ptr<PyScenario>>(m, "Scenario", "A scenario config made into a model (phasmid.Scenario wraps it).")
      .def_static("load", [](const std::string& path, std::vector<std::string> sets) {
        return make_scenario(config_stage([&] { return config::load_config(path); }), std::move(sets));
      }, py::arg("path"), py::arg("sets") = std::vector<std::string>{})
      .def_static("loads", [](const std::string& text, const std::string& origin, std::vector<std::string> sets) {
        return make_scenario(config_stage([&] { return config::parse_config(text, origin); }), std::move(sets));
      }, py::arg("text"), py::arg("origin") = "<string>", py::arg("sets") = std::vector<std::string>{})
      .def("with_sets", [](const PyScenario& s, const std::vector<std::string>& more) {
        std::vector<std::string> sets = s.sets;
        sets.insert(sets.end(), more.begin(), more.end());
        return make_scenario(s.cfg, sets);
      })
      .def_property_readonly("kind", [](const PyScenario& s) { return s.scenario->kind(); })
      .def_property_readonly("path", [](const PyScenario& s) { return s.cfg.path; })
      .def_property_readonly("inputs", [](const PyScenario& s) { return s.inputs(); })
      .def_property_readonly("sets", [](const PyScenario& s) { return s.sets; })
      .def_property_readonly("config_text", [](const PyScenario& s) { return config::resolved_config_text(s.cfg, s.sets); })
      .def_property_readonly("is_ode", [](const PyScenario& s) { return s.scenario->ode_model() != nullptr; })
      .def("parameter_records", &parameter_records)
      .def("feature_catalogue", [](const PyScenario& s) {
        py::list out;
        for (const auto& f : s.scenario->feature_catalogue())
          out.append(py::make_tuple(f.name, f.unit, f.differentiable, f.description));
        return out;
      })
      .def("simulate", &simulate, py::arg("options") = Options{});
}

py::list event_records(const Simulation& s) {
  py::list out;
  for (const auto& e : s.solution().events) out.append(py::make_tuple(e.t, e.root, e.direction));
  return out;
}

void bind_simulation_class(py::module_& m) {
  py::class_<Simulation>(m, "Simulation", "One run of a scenario (phasmid.SimulationResult wraps it).")
      .def_property_readonly("time", [](py::object self) {
        return view(self.cast<const Simulation&>().solution().t, self);
      })
      .def_property_readonly("y", [](py::object self) {
        const solver::SolveResult& r = self.cast<const Simulation&>().solution();
        const auto n = static_cast<py::ssize_t>(r.n_states), rows = static_cast<py::ssize_t>(r.t.size());
        return view(r.y.data(), {rows, n}, {n * static_cast<py::ssize_t>(sizeof(double)), sizeof(double)}, self);
      }, "n_times x n_states, the integrated states (units of state_units), a view")
      .def_property_readonly("has_solution", [](const Simulation& s) { return s.run->solution() != nullptr; })
      .def_property_readonly("state_names", [](const Simulation& s) {
        std::vector<std::string> names;
        if (auto* m = s.scenario->scenario->ode_model()) for (const auto& st : m->states()) names.push_back(st.name);
        return names;
      })
      .def_property_readonly("state_units", [](const Simulation& s) {
        std::vector<std::string> units;
        if (auto* m = s.scenario->scenario->ode_model()) for (const auto& st : m->states()) units.push_back(st.unit);
        return units;
      })
      .def("degree_names", [](const Simulation& s) {
        std::vector<std::string> names;
        for (const auto& kv : s.degrees) names.push_back(kv.first);
        return names;
      })
      .def("degrees", [](py::object self, const std::string& name) {
        const Simulation& s = self.cast<const Simulation&>();
        auto it = s.degrees.find(name);
        if (it == s.degrees.end()) throw py::key_error(name);
        return view(it->second, self);
      })
      .def("feature_records", [](const Simulation& s) { return feature_records(s.run->features()); })
      .def("event_records", &event_records)
      .def("root_states", [](const Simulation& s) {
        // The roots the run located, in the order OdeScenario::run passed them.
        const model::OdeModel* m = s.scenario->scenario->ode_model();
        std::vector<size_t> states;
        for (const auto& r : features::feature_roots(*m, m->parameters().values())) states.push_back(r.state);
        return states;
      })
      .def("notes", [](const Simulation& s) { return s.run->notes(); })
      .def("summary", [](const Simulation& s) { return s.run->summary(); })
      .def("save", &Simulation::save, py::arg("path"));
}

}  // namespace

void bind_scenario(py::module_& m) {
  bind_scenario_class(m);
  bind_simulation_class(m);
}

}  // namespace phasmid::python
