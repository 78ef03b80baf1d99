// phasmid continue CONFIG [-o OUT.h5] [--set NAME=VALUE ...] [-q] [--json]
#include <cstdio>
#include <iostream>

#include "app/options.hpp"
#include "app/verb.hpp"
#include "app/write_output.hpp"
#include "common/error.hpp"
#include "config/config.hpp"
#include "config/continuation_section.hpp"
#include "continuation/continuation_h5.hpp"
#include "io/h5_file.hpp"
#include "io/output_path.hpp"
#include "io/trajectory_writer.hpp"
#include "model/ode_model.hpp"

namespace phasmid::app {
namespace {
struct ContinueArgs {
  std::string config, out = "continuation.h5";
  std::vector<std::string> sets;
  bool quiet = false, json = false, trace = false;
};

void print_json(const continuation::Branch& b) {
  std::cout << "{\"parameter\": \"" << b.parameter << "\", \"points\": " << b.points.size() << ", \"special_points\": [";
  for (size_t i = 0; i < b.special.size(); ++i) {
    const auto& s = b.special[i];
    std::cout << (i ? ", " : "") << "{\"kind\": \"" << s.kind << "\", \"index\": " << s.index
              << ", \"parameter\": " << s.parameter << ", \"period_ms\": " << s.period_ms << "}";
  }
  std::cout << "]}\n";
}

void print_point(const continuation::ContinuationOptions& options, const continuation::BranchPoint& b, size_t k,
                 bool trace) {
  std::cerr << "phasmid continue: point " << k << ": " << options.parameter << " = " << b.parameter << ", period "
            << b.period_ms << " ms, " << (b.stable ? "stable" : "unstable")
            << (b.neutral.empty() ? "" : " (" + std::to_string(b.neutral.size()) + " neutral)") << ", "
            << b.newton_iterations << " Newton iterations\n";
  if (!trace) return;
  std::cerr << "phasmid continue:   |mu|:";
  for (size_t i = 0; i < b.multipliers.size() && i < 6; ++i) std::cerr << " " << std::abs(b.multipliers[i]);
  for (size_t j = 0; j < b.features.size() && j < options.features.size(); ++j)
    std::cerr << (j ? ", " : "; ") << options.features[j] << " " << b.features[j];
  std::cerr << "\n";
}

int run_continue(const ContinueArgs& a) {
  config::Config cfg = config::load_config(a.config);
  io::check_output_path(a.out, {a.config}, {a.out + ".tmp", a.out + ".partial", a.out + ".partial.tmp"});
  const auto lock = lock_output(a.out);  // also covers OUT.partial, written only by OUT's holder
  auto scenario = config::build_scenario(cfg, a.sets);
  const model::OdeModel* model = scenario->ode_model();
  if (!model)
    throw Error(cfg.path + ": model type " + scenario->kind() + " is not an ODE system; continuation needs one");
  auto options = config::continuation_options(cfg, *model, config::bdf_simulation_settings(cfg, scenario.get()));
  // The branch so far goes to "<out>.partial" after every point, so that a run stopped after
  // hours keeps its points; the complete file replaces it at the end.
  const std::string partial = a.out + ".partial";
  options.on_point = [&, model](const continuation::Branch& br) {
    if (!a.quiet) print_point(options, br.points.back(), br.points.size() - 1, a.trace);
    io::H5Writer w(partial);
    write_run_file(w, cfg, a.sets, *scenario);
    io::write_parameters(w, *model, model->parameters().values());
    continuation::write_branch_h5(w, *model, br);
    w.set_attribute("/continuation", "end", "");  // not ended: the last special point is not the end
    w.set_attribute("/continuation", "partial",
                    "the branch so far: the run was still going when this file was written (" + a.out + " replaces it at the end)");
    w.commit();
  };
  if (a.trace)
    options.shooting.on_iteration = [model, &options](int it, double res, size_t worst, bool monodromy) {
      std::cerr << "phasmid continue:   iteration " << it << ": residual " << res << " (largest: "
                << continuation::row_name(*model, options.shooting, worst) << ")" << (monodromy ? " (monodromy)" : "") << "\n";
    };
  const continuation::Branch branch = continuation::continue_cycles(*model, model->parameters().values(), options);
  io::H5Writer w(a.out);
  write_run_file(w, cfg, a.sets, *scenario);
  io::write_parameters(w, *model, model->parameters().values());
  continuation::write_branch_h5(w, *model, branch);
  w.commit();
  std::remove(partial.c_str());
  if (a.json) print_json(branch);
  else if (!a.quiet) std::cout << continuation::format_summary(branch);
  if (!a.quiet) std::cerr << "phasmid continue: wrote " << a.out << "\n";
  return 0;
}

const RegisterVerb reg{{"continue", "Follow a periodic orbit (gait cycle) as one parameter moves: period, features, Floquet multipliers, bifurcations",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<ContinueArgs>();
                          add_config_arg(sub, a->config, "scenario config (TOML) with a [continuation] section");
                          add_output(sub, a->out, "continuation.h5");
                          add_sets(sub, a->sets);
                          add_quiet(sub, a->quiet);
                          add_json(sub, a->json);
                          sub.add_flag("--trace", a->trace, "print the residual of every corrector iteration, and each point's largest multipliers and tracked features");
                          return std::function<int()>([a] { return run_continue(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
