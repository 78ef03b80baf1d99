#include "simroach2/tables.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "common/embedded.hpp"
#include "common/error.hpp"
#include "build_info.hpp"

namespace phasmid::simroach2 {
namespace {

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) cells.push_back(cell), cell.clear();
    else if (c != '\r') cell += c;
  }
  cells.push_back(cell);
  return cells;
}

}  // namespace

std::size_t Table::column(const std::string& name) const {
  for (std::size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == name) return i;
  throw Error(fmt::format("{}: no column '{}'", origin, name));
}

const std::string& Table::text(std::size_t row, const std::string& name) const { return rows.at(row)[column(name)]; }

double Table::number(std::size_t row, const std::string& name) const {
  const std::string& s = text(row, name);
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != s.size()) throw Error(fmt::format("{}: row {} column '{}': '{}' is not a number", origin, row + 1, name, s));
  return v;
}

Table parse_table(const std::string& text, const std::string& origin) {
  Table t;
  t.origin = origin;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    auto cells = split_csv_line(line);
    if (t.columns.empty()) {
      t.columns = std::move(cells);
      continue;
    }
    if (cells.size() != t.columns.size())
      throw Error(fmt::format("{}:{}: expected {} fields, found {}", origin, line_no, t.columns.size(), cells.size()));
    t.rows.push_back(std::move(cells));
  }
  if (t.columns.empty()) throw Error(fmt::format("{}: no header line", origin));
  return t;
}

Table load_table(const std::string& file) {
  const std::string key = "datasets/simroach2/" + file;
  const auto& files = embedded::files();
  if (auto it = files.find(key); it != files.end()) return parse_table(it->second, key);
  const std::string path = std::string(PHASMID_SOURCE_DIR) + "/" + key;
  std::ifstream in(path);
  if (!in) throw Error(fmt::format("{}: SimRoach2 table not embedded and not readable", path));
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_table(ss.str(), path);
}

int printed_decimals(const std::string& number) {
  const auto dot = number.find('.');
  if (dot == std::string::npos) return 0;
  return static_cast<int>(number.size() - dot - 1);
}

}  // namespace phasmid::simroach2
