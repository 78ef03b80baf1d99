#pragma once
// The walking models the benchmarks time, by key: "joint" (the isolated middle FTi joint),
// "leg" (the middle leg, ThC set A.17), otherwise the three legs (tetrapod); and the parsing of
// their list arguments.
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "model/leg_network.hpp"
#include "model/network_builder.hpp"

namespace phasmid::bench {

inline std::unique_ptr<model::NetworkModel> build_walking_model(const std::string& key, model::MotoneuronModel mn) {
  if (key == "joint") return model::build_single_joint_model("middle", model::JointType::Fti, "", mn);
  if (key == "leg") {
    model::LegOptions o;
    o.thc_set = "A.17";
    o.motoneuron = mn;
    return model::build_leg_model("middle", o);
  }
  model::ThreeLegOptions o;
  o.motoneuron = mn;
  return model::build_three_leg_model(o);
}

// "a,b,c" -> {"a", "b", "c"}: the benchmarks' comma-separated arguments.
inline std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string x; std::getline(ss, x, ',');) out.push_back(x);
  return out;
}

}  // namespace phasmid::bench
