#include "config/model_section.hpp"

#include "common/error.hpp"

namespace phasmid::config {

std::string TomlModelSection::where(const std::string& key) const {
  const toml::node* n = table_.get(key);
  return n ? config::where(cfg_, *n) : config::where(cfg_, table_);
}

std::string TomlModelSection::text(const std::string& key, const std::string& fallback) const {
  const toml::node* n = table_.get(key);
  return n ? config::text(cfg_, *n, key) : fallback;
}

double TomlModelSection::number(const std::string& key, double fallback) const {
  const toml::node* n = table_.get(key);
  return n ? config::number(cfg_, *n, key) : fallback;
}

bool TomlModelSection::boolean(const std::string& key, bool fallback) const {
  const toml::node* n = table_.get(key);
  return n ? config::boolean(cfg_, *n, key) : fallback;
}

std::vector<scenario::ModelSection::Located> TomlModelSection::numbers(const std::string& key,
                                                                       const std::string& what) const {
  std::vector<Located> out;
  const toml::node* n = table_.get(key);
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a || a->empty()) throw Error(where(key) + ": " + key + " must be " + what);
  for (const toml::node& e : *a) out.push_back({config::number(cfg_, e, key), config::where(cfg_, e)});
  return out;
}

}  // namespace phasmid::config
