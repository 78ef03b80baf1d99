// phasmid simroach2 <task>: the SimRoach2 data and design tools (docs/simroach2.md).
//   check-muscles [--json]   Table 3: active force at -60 mV implied by amplitude and y-offset
//   damping ...              Sect. 3.5.1: critical damping over a joint's range (eqs. 15-20)
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/verb.hpp"
#include "common/error.hpp"
#include "common/units.hpp"
#include "simroach2/muscle_check.hpp"
#include "simroach2/passive_joint.hpp"

namespace {

int check_muscles_cmd(bool json) {
  using namespace phasmid::simroach2;
  const auto rows = check_muscles(load_table("table3_muscle_activation.csv"));
  int consistent = 0;
  for (const auto& r : rows) consistent += r.consistent;
  if (json) {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& r : rows)
      j.push_back({{"joint", r.joint}, {"muscle", r.muscle}, {"amplitude_N", r.amplitude_N},
                   {"y_offset_mN", r.y_offset_mN}, {"force_at_rest_mN", r.force_at_rest_mN},
                   {"rounding_bound_mN", r.rounding_bound_mN}, {"consistent", r.consistent}});
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::cout << "joint     muscle    amplitude_N  y_offset_mN  force_at_rest_mN  rounding_bound_mN  consistent\n";
  for (const auto& r : rows)
    std::cout << fmt::format("{:<9} {:<9} {:>11.4f} {:>12.3f} {:>17.3f} {:>18.4f}  {}\n", r.joint, r.muscle,
                             r.amplitude_N, r.y_offset_mN, r.force_at_rest_mN, r.rounding_bound_mN,
                             r.consistent ? "yes" : "NO");
  std::cout << fmt::format("{} of {} muscles have zero active force at -60 mV to printing precision\n", consistent,
                           rows.size());
  return 0;
}

struct DampingOptions {
  double k = 0, inertia = 0, proximal_mm = 0, distal_mm = 0, theta_min_deg = 0, theta_max_deg = 0;
  int n = 181;
  bool json = false;
};

int damping_cmd(const DampingOptions& o) {
  using namespace phasmid::simroach2;
  const double deg = phasmid::units::kRadPerDeg;
  if (!(o.theta_max_deg > o.theta_min_deg)) throw phasmid::Error("--theta-max must exceed --theta-min");
  const auto d = critical_damping_over_range(o.k, o.inertia, {o.proximal_mm * 1e-3, o.distal_mm * 1e-3},
                                             o.theta_min_deg * deg, o.theta_max_deg * deg, o.n);
  if (o.json) {
    nlohmann::json j = {{"c_max_Ns_per_m", d.c_max_Ns_per_m},
                        {"c_max_mg_per_s", d.c_max_Ns_per_m / kNsPerM_per_mgPerS},
                        {"theta_at_max_deg", d.theta_at_max_rad / deg}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << fmt::format("critical damping over {}..{} deg: c_max = {:.6g} N s/m ({:.6g} mg/s) at {:.2f} deg\n",
                             o.theta_min_deg, o.theta_max_deg, d.c_max_Ns_per_m,
                             d.c_max_Ns_per_m / kNsPerM_per_mgPerS, d.theta_at_max_rad / deg);
  }
  return 0;
}

phasmid::app::RegisterVerb reg{
    {"simroach2", "Tools for the SimRoach2 robot data, not a model run: check-muscles (Table 3), damping (eqs. 15-20)", [](CLI::App& sub) {
       sub.require_subcommand(1);
       auto json = std::make_shared<bool>(false);
       auto* check = sub.add_subcommand("check-muscles", "Table 3: active force at -60 mV of all 60 muscles");
       check->add_flag("--json", *json, "JSON rows");
       auto o = std::make_shared<DampingOptions>();
       auto* damp = sub.add_subcommand("damping", "critical damping of a joint spring over its range (eqs. 15-20)");
       damp->add_option("--k", o->k, "spring stiffness, N/m (Table 2)")->required();
       damp->add_option("--inertia", o->inertia, "limb inertia about the joint, kg m^2")->required();
       damp->add_option("--proximal-mm", o->proximal_mm, "spring attachment on the proximal segment, mm")->required();
       damp->add_option("--distal-mm", o->distal_mm, "spring attachment on the distal segment (r), mm")->required();
       damp->add_option("--theta-min", o->theta_min_deg, "joint range start, deg")->required();
       damp->add_option("--theta-max", o->theta_max_deg, "joint range end, deg")->required();
       damp->add_option("--samples", o->n, "angles sampled over the range");
       damp->add_flag("--json", o->json, "JSON output");
       return std::function<int()>([&sub, check, json, o] {
         if (sub.got_subcommand(check)) return check_muscles_cmd(*json);
         return damping_cmd(*o);
       });
     }}};

}  // namespace
