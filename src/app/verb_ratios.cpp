// phasmid ratios --joint thc|ctr|fti --angles A,B [--json]: eqs. (2.43)-(2.45).
#include <nlohmann/json.hpp>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "app/verb.hpp"
#include "common/error.hpp"
#include "model/joint.hpp"

namespace phasmid::app {
namespace {
struct RatiosArgs {
  std::string joint, angles;
  bool json = false;
};

int run_ratios(const RatiosArgs& a) {
  model::JointType j = model::parse_joint(a.joint);
  std::vector<double> angles;
  std::stringstream ss(a.angles);
  for (std::string item; std::getline(ss, item, ',');) {
    char* end = nullptr;
    double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0') throw Error("--angles: '" + item + "' is not a number (degrees)");
    if (v <= 0 || v >= 180) throw Error("--angles: " + item + " deg is outside the joint's range (0, 180)");
    angles.push_back(v);
  }
  if (angles.empty()) throw Error("--angles needs at least one angle in degrees");
  const char* what = j == model::JointType::Fti ? "a_FE = k_F/k_E (2.43)"
                     : j == model::JointType::Ctr ? "a_LD = k_D/k_L (2.44)" : "a_PR = k_R/k_P (2.45)";
  nlohmann::json out = nlohmann::json::array();
  for (double ang : angles) {
    double r = model::spring_constant_ratio(j, ang);
    if (a.json) out.push_back({{"joint", a.joint}, {"angle_deg", ang}, {"ratio", r}, {"definition", what}});
    else std::cout << a.joint << "  " << std::setw(7) << ang << " deg  " << what << " = " << std::setprecision(5) << r << "\n";
  }
  if (a.json) std::cout << out.dump(2) << "\n";
  return 0;
}

const RegisterVerb reg{{"ratios", "Print the spring-constant ratios at stationary extremal angles (eqs. 2.43-2.45)",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<RatiosArgs>();
                          sub.add_option("--joint", a->joint, "thc, ctr or fti")->required();
                          sub.add_option("--angles", a->angles, "comma-separated angles in degrees")->required();
                          sub.add_flag("--json", a->json, "JSON output");
                          return std::function<int()>([a] { return run_ratios(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
