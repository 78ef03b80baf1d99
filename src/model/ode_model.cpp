#include "model/ode_model.hpp"

#include "common/error.hpp"

namespace phasmid::model {

size_t OdeModel::add_state(std::string name, std::string unit) {
  states_.push_back({std::move(name), std::move(unit)});
  return states_.size() - 1;
}

const ContactLeg* OdeModel::contact_leg(const std::string& leg) const {
  for (const ContactLeg& l : structure_.contact_legs)
    if (l.leg == leg) return &l;
  return nullptr;
}

size_t OdeModel::state_index(const std::string& name) const {
  for (size_t i = 0; i < states_.size(); ++i)
    if (states_[i].name == name) return i;
  throw Error("unknown state '" + name + "'");
}

}  // namespace phasmid::model
