#pragma once
// Every number of a model is a named parameter with a unit and a source (docs/model.md).
// A ParameterSet is the model's contiguous parameter vector plus that metadata; the
// equations read values by index, users address them by name.
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

namespace phasmid::model {

struct Parameter {
  std::string name;         // e.g. "middle.fti.k_E.flexion"
  double value = 0.0;
  std::string unit;         // e.g. "mN/mm^2"
  std::string source;       // e.g. "Knops 2013, Table A.14"
  std::string description;  // what it does, in one line
  double lower = -std::numeric_limits<double>::infinity();  // physically admissible range
  double upper = std::numeric_limits<double>::infinity();
};

class ParameterSet {
 public:
  // Adds a parameter and returns its index; a second add of the same name is a bug.
  size_t add(Parameter p);
  size_t size() const { return params_.size(); }
  bool contains(const std::string& name) const { return index_.count(name) > 0; }
  size_t index(const std::string& name) const;  // throws Error naming the unknown parameter
  const Parameter& at(size_t i) const { return params_[i]; }
  const Parameter& at(const std::string& name) const { return params_[index(name)]; }
  double value(const std::string& name) const { return at(name).value; }
  // Sets a value after checking name and admissible range; `origin` (e.g. "--set",
  // "cfg.toml:12") prefixes any error message.
  void set(const std::string& name, double value, const std::string& origin = "");
  void set(size_t i, double value) { params_[i].value = value; }
  std::vector<double> values() const;
  std::vector<std::string> names() const;
  const std::vector<Parameter>& all() const { return params_; }

 private:
  std::vector<Parameter> params_;
  std::unordered_map<std::string, size_t> index_;
};

// Parses "NAME=VALUE" as given to --set; throws Error on malformed input.
std::pair<std::string, double> parse_assignment(const std::string& text);

}  // namespace phasmid::model
