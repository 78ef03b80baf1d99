#pragma once
// The [model] table of a parsed config as the scenario::ModelSection a kind's factory reads
// (scenario/registry.hpp): every error names file:line and the key.
#include <string>
#include <vector>

#include "config/toml_util.hpp"
#include "scenario/registry.hpp"

namespace phasmid::config {

class TomlModelSection : public scenario::ModelSection {
 public:
  TomlModelSection(const Config& cfg, const toml::table& table) : cfg_(cfg), table_(table) {}
  bool has(const std::string& key) const override { return table_.get(key) != nullptr; }
  std::string text(const std::string& key, const std::string& fallback) const override;
  double number(const std::string& key, double fallback) const override;
  bool boolean(const std::string& key, bool fallback) const override;
  std::vector<Located> numbers(const std::string& key, const std::string& what) const override;
  std::string where(const std::string& key) const override;

 private:
  const Config& cfg_;
  const toml::table& table_;
};

}  // namespace phasmid::config
