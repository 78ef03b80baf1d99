#include "config/resume_spec.hpp"

#include <charconv>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

namespace phasmid::config {
namespace {

// The shortest text that reads back as the same double (std::to_chars), so that the line names
// the value as a person wrote it ("7", "300", "0.1") and still tells every bit apart.
std::string shortest(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string value_text(const toml::node& n) {
  if (auto s = n.value_exact<std::string>()) return nlohmann::json(*s).dump(-1, ' ', true);
  if (auto b = n.value_exact<bool>()) return *b ? "true" : "false";
  if (auto d = n.value<double>()) return shortest(*d);  // integers and floats alike
  std::ostringstream os;  // dates and times, as TOML writes them
  n.visit([&](const auto& x) { os << x; });
  return os.str();
}

void walk(const toml::node& n, const std::string& path, std::string& out) {
  if (auto t = n.as_table()) {
    for (auto& [k, v] : *t) walk(v, path.empty() ? std::string(k.str()) : path + "." + std::string(k.str()), out);
  } else if (auto a = n.as_array()) {
    for (std::size_t i = 0; i < a->size(); ++i) walk(*a->get(i), path + "[" + std::to_string(i) + "]", out);
    if (a->empty()) out += path + " = []\n";
  } else {
    out += path + " = " + value_text(n) + "\n";
  }
}

}  // namespace

std::string resume_spec(const Config& cfg, const model::ParameterSet& resolved) {
  static const std::set<std::string> compared = {"model", "simulation", "triggers", "sweep", "cruse1980"};
  std::string out;
  for (const auto& p : resolved.all()) out += "model parameter " + p.name + " = " + shortest(p.value) + "\n";
  for (auto& [k, v] : cfg.table) {
    const std::string section(k.str());
    if (!compared.count(section)) continue;
    std::string lines;
    walk(v, section, lines);
    for (std::size_t at = 0, end; at < lines.size(); at = end + 1) {
      end = lines.find('\n', at);
      const std::string line = lines.substr(at, end - at);
      if (line.rfind("model.description = ", 0) != 0) out += line + "\n";
    }
  }
  return out;
}

}  // namespace phasmid::config
