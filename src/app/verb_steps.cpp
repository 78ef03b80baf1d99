// phasmid steps RECORDING [--leg L2]... [-o STEPS.h5] [--json]: the step cycles of a recording
// (docs/recordings.md): per leg, the steps the touchdowns cut it into, which of them count, the
// median period, the duty factor, and each angle's mean and SD over phase.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/verb.hpp"
#include "app/write_output.hpp"
#include "common/error.hpp"
#include "features/step_cycles.hpp"
#include "fit/kinematic_data.hpp"
#include "io/h5_file.hpp"
#include "io/output_path.hpp"

namespace phasmid::app {
namespace {
struct StepsArgs {
  std::string recording, out;
  std::vector<std::string> legs;
  double frame_rate_hz = 0;
  features::StepCycleOptions options;
  bool json = false, quiet = false;
};

using LegCycles = std::vector<std::pair<std::string, features::StepCycles>>;

// The channels of `leg` and their samples.
LegCycles analyse(const fit::KinematicData& d, const StepsArgs& a) {
  std::vector<std::string> legs = a.legs;
  if (legs.empty())
    for (const auto& [leg, s] : d.stances) legs.push_back(leg);
  if (legs.empty()) throw Error(d.source + ": no contact data (contact.<leg> columns or fields): no steps to find");
  LegCycles out;
  for (const std::string& leg : legs) {
    auto it = d.stances.find(leg);
    if (it == d.stances.end()) throw Error(d.source + ": no contact data for leg '" + leg + "'");
    std::vector<std::string> channels;
    std::vector<std::vector<double>> samples;
    for (size_t c = 0; c < d.channels.size(); ++c)
      if (d.channels[c].compare(0, leg.size() + 1, leg + ".") == 0)
        channels.push_back(d.channels[c]), samples.push_back(d.angles_deg[c]);
    if (channels.empty()) throw Error(d.source + ": no angle of leg '" + leg + "'");
    out.emplace_back(leg, features::step_cycles(d.time_ms, channels, samples, it->second, a.options, d.source + ": " + leg));
  }
  return out;
}

double finite_or_nan(double v) { return std::isfinite(v) ? v : std::nan(""); }

void print_table(const fit::KinematicData& d, const LegCycles& legs) {
  std::printf("%s: %zu samples, %.4g s\n", d.source.c_str(), d.time_ms.size(), (d.time_ms.back() - d.time_ms.front()) / 1000);
  std::printf("%-6s %5s %5s %12s %10s %8s %8s\n", "leg", "steps", "kept", "period ms", "(SD)", "duty", "(SD)");
  for (const auto& [leg, c] : legs)
    std::printf("%-6s %5zu %5zu %12.4g %10.3g %8.3f %8.3f\n", leg.c_str(), c.steps.size(), c.kept(), c.median_period_ms,
                finite_or_nan(c.period_sd_ms), c.duty_factor, finite_or_nan(c.duty_factor_sd));
  std::printf("%-10s %9s %9s %14s\n", "angle", "min deg", "max deg", "step SD deg");
  for (const auto& [leg, c] : legs)
    for (size_t k = 0; k < c.channels.size(); ++k) {
      double lo = INFINITY, hi = -INFINITY, sd = 0;
      for (size_t b = 0; b < c.phase.size(); ++b)
        lo = std::min(lo, c.mean_deg[k][b]), hi = std::max(hi, c.mean_deg[k][b]), sd += c.sd_deg[k][b];
      std::printf("%-10s %9.2f %9.2f %14.3g\n", c.channels[k].c_str(), lo, hi, sd / static_cast<double>(c.phase.size()));
    }
  for (const auto& [leg, c] : legs)
    for (size_t i = 0; i < c.steps.size(); ++i)
      if (!c.steps[i].dropped.empty())
        std::printf("dropped %s step %zu (%.1f-%.1f ms): %s\n", leg.c_str(), i + 1, c.steps[i].touchdown_ms,
                    c.steps[i].next_touchdown_ms, c.steps[i].dropped.c_str());
}

nlohmann::json to_json(const LegCycles& legs) {
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  auto nums = [&](const std::vector<double>& v) {
    nlohmann::json a = nlohmann::json::array();
    for (double x : v) a.push_back(num(x));
    return a;
  };
  nlohmann::json j;
  for (const auto& [leg, c] : legs) {
    nlohmann::json steps = nlohmann::json::array();
    for (const auto& s : c.steps)
      steps.push_back({{"touchdown_ms", s.touchdown_ms}, {"liftoff_ms", num(s.liftoff_ms)},
                       {"next_touchdown_ms", s.next_touchdown_ms}, {"dropped", s.dropped}});
    nlohmann::json ch;
    for (size_t k = 0; k < c.channels.size(); ++k) ch[c.channels[k]] = {{"mean_deg", nums(c.mean_deg[k])}, {"sd_deg", nums(c.sd_deg[k])}};
    j[leg] = {{"median_period_ms", c.median_period_ms}, {"mean_period_ms", c.mean_period_ms}, {"period_sd_ms", num(c.period_sd_ms)},
              {"duty_factor", c.duty_factor}, {"duty_factor_sd", num(c.duty_factor_sd)}, {"kept", c.kept()},
              {"steps", steps}, {"phase", nums(c.phase)}, {"channels", ch}};
  }
  return j;
}

// /steps/<leg>/... (docs/hdf5.md).
void write_h5(const StepsArgs& a, const LegCycles& legs) {
  io::H5Writer w(a.out);
  w.write_run_info({"", command_line()});
  w.ensure_group("/steps");
  w.set_attribute("/steps", "source", a.recording);
  w.set_attribute("/steps", "bins", static_cast<double>(a.options.bins));
  w.set_attribute("/steps", "discard_steps", static_cast<double>(a.options.discard_steps));
  w.set_attribute("/steps", "max_period_deviation", a.options.max_period_deviation);
  for (const auto& [leg, c] : legs) {
    const std::string g = "/steps/" + leg;
    std::vector<double> td, lo, next;
    std::vector<std::int64_t> kept;
    std::vector<std::string> why;
    for (const auto& s : c.steps)
      td.push_back(s.touchdown_ms), lo.push_back(s.liftoff_ms), next.push_back(s.next_touchdown_ms),
          kept.push_back(s.dropped.empty()), why.push_back(s.dropped);
    w.write(g + "/touchdown_ms", td, "ms");
    w.write(g + "/liftoff_ms", lo, "ms");
    w.write(g + "/next_touchdown_ms", next, "ms");
    w.write(g + "/kept", kept, "1");
    w.write(g + "/dropped", why);
    w.write(g + "/phase", c.phase, "1");
    w.write(g + "/channels", c.channels);
    for (size_t k = 0; k < c.channels.size(); ++k) {
      w.write(g + "/mean_deg/" + c.channels[k], c.mean_deg[k], "deg");
      w.write(g + "/sd_deg/" + c.channels[k], c.sd_deg[k], "deg");
    }
    w.set_attribute(g, "median_period_ms", c.median_period_ms);
    w.set_attribute(g, "mean_period_ms", c.mean_period_ms);
    w.set_attribute(g, "period_sd_ms", c.period_sd_ms);
    w.set_attribute(g, "duty_factor", c.duty_factor);
    w.set_attribute(g, "duty_factor_sd", c.duty_factor_sd);
  }
  w.commit();
}

int run(const StepsArgs& a) {
  if (const std::string why = a.options.invalid_reason(); !why.empty()) throw Error("phasmid steps: " + why);
  std::unique_ptr<io::OutputLock> lock;
  if (!a.out.empty()) {
    io::check_output_path(a.out, {a.recording});
    lock = lock_output(a.out);
  }
  const fit::KinematicData d = fit::read_recording(a.recording, a.frame_rate_hz, a.legs);
  const LegCycles legs = analyse(d, a);
  if (!a.out.empty()) write_h5(a, legs);
  if (a.json) std::cout << to_json(legs).dump(1) << "\n";
  else if (!a.quiet) print_table(d, legs);
  return 0;
}

const RegisterVerb reg{{"steps", "Step cycles of a recording (MAT trial or CSV): period, duty factor, angles over phase",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<StepsArgs>();
                          sub.add_option("RECORDING", a->recording, "a Stick Insect Locomotion trial (.mat) or a phasmid CSV with contact columns")->required();
                          sub.add_option("--leg", a->legs, "legs to analyse (default: every leg with contact data)");
                          sub.add_option("--bins", a->options.bins, "phase bins per step (default 50)");
                          sub.add_option("--discard-steps", a->options.discard_steps, "first steps dropped as the start transient (default 1)");
                          sub.add_option("--max-period-deviation", a->options.max_period_deviation,
                                         "drop steps whose period is further than this fraction from the median (default 0.3)");
                          sub.add_option("--frame-rate", a->frame_rate_hz, "frame rate (Hz) of a CSV with a frame column");
                          sub.add_option("-o,--output", a->out, "also write /steps to this HDF5 file");
                          sub.add_flag("--json", a->json, "print the summary as JSON");
                          sub.add_flag("-q,--quiet", a->quiet, "no table");
                          return std::function<int()>([a] { return run(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
