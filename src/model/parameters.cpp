#include "model/parameters.hpp"

#include <cmath>
#include <sstream>

#include "common/error.hpp"

namespace phasmid::model {

size_t ParameterSet::add(Parameter p) {
  if (index_.count(p.name)) throw Error("internal: parameter defined twice: " + p.name);
  index_[p.name] = params_.size();
  params_.push_back(std::move(p));
  return params_.size() - 1;
}

size_t ParameterSet::index(const std::string& name) const {
  auto it = index_.find(name);
  if (it == index_.end()) {
    // Suggest the closest known name (same suffix) to make typos obvious.
    std::string hint;
    auto dot = name.rfind('.');
    std::string tail = dot == std::string::npos ? name : name.substr(dot);
    for (auto& p : params_)
      if (p.name.size() >= tail.size() && p.name.compare(p.name.size() - tail.size(), tail.size(), tail) == 0) {
        hint = " (did you mean '" + p.name + "'?)";
        break;
      }
    throw Error("unknown parameter '" + name + "'" + hint + "; `phasmid params CONFIG` lists them");
  }
  return it->second;
}

void ParameterSet::set(const std::string& name, double value, const std::string& origin) {
  std::string where = origin.empty() ? "" : origin + ": ";
  size_t i;
  try {
    i = index(name);
  } catch (const Error& e) {
    throw Error(where + e.what());
  }
  const Parameter& p = params_[i];
  if (!std::isfinite(value) || value < p.lower || value > p.upper) {
    std::ostringstream os;
    os << where << "impossible value " << value << " for parameter '" << name << "' (allowed range ["
       << p.lower << ", " << p.upper << "] " << p.unit << ")";
    throw Error(os.str());
  }
  params_[i].value = value;
}

std::vector<double> ParameterSet::values() const {
  std::vector<double> v;
  v.reserve(params_.size());
  for (auto& p : params_) v.push_back(p.value);
  return v;
}

std::vector<std::string> ParameterSet::names() const {
  std::vector<std::string> v;
  for (auto& p : params_) v.push_back(p.name);
  return v;
}

std::pair<std::string, double> parse_assignment(const std::string& text) {
  auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw Error("--set expects NAME=VALUE, got '" + text + "'");
  std::string name = text.substr(0, eq), rhs = text.substr(eq + 1);
  char* end = nullptr;
  double v = std::strtod(rhs.c_str(), &end);
  if (end == rhs.c_str() || *end != '\0') throw Error("--set " + name + ": '" + rhs + "' is not a number");
  return {name, v};
}

}  // namespace phasmid::model
