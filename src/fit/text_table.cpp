#include "fit/text_table.hpp"

#include <cmath>
#include <cstdlib>
#include <limits>

#include "common/error.hpp"

namespace phasmid::fit {
namespace {
std::string trim(const std::string& s) {
  size_t a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

std::vector<std::string> split(const std::string& line, char delim, const std::string& where) {
  std::vector<std::string> cells;
  std::string cur;
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    char c = line[i];
    if (c == '"') {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"') {
        cur += '"';
        ++i;
      } else {
        quoted = !quoted;
      }
    } else if (c == delim && !quoted) {
      cells.push_back(trim(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (quoted) throw Error(where + ": unterminated quoted field");
  cells.push_back(trim(cur));
  return cells;
}
}  // namespace

TextTable parse_text_table(const std::string& text, const std::string& origin, char delimiter) {
  TextTable t;
  size_t line_no = 0, pos = 0;
  const std::string delim_name = delimiter == '\t' ? "tab" : std::string("'") + delimiter + "'";
  while (pos <= text.size()) {
    size_t nl = text.find('\n', pos);
    std::string line = text.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos);
    pos = nl == std::string::npos ? text.size() + 1 : nl + 1;
    ++line_no;
    if (line_no == 1 && line.size() >= 3 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line = line.substr(3);  // BOM
    std::string tl = trim(line);
    if (tl.empty() || tl[0] == '#') continue;
    const std::string where = origin + ":" + std::to_string(line_no);
    if (line.find('\0') != std::string::npos) throw Error(where + ": NUL byte (not a text file)");
    std::vector<std::string> cells = split(line, delimiter, where);
    if (t.header.empty()) {
      t.header_line = line_no;
      t.header = cells;
      if (cells.size() < 2)
        throw Error(where + ": header has a single column (expected " + delim_name + "-separated columns)");
      for (size_t i = 0; i < cells.size(); ++i) {
        if (cells[i].empty()) throw Error(where + ": empty column name in header (column " + std::to_string(i + 1) + ")");
        for (size_t j = 0; j < i; ++j)
          if (cells[j] == cells[i]) throw Error(where + ": column '" + cells[i] + "' appears twice in the header");
      }
      continue;
    }
    if (cells.size() != t.header.size())
      throw Error(where + ": " + std::to_string(cells.size()) + " " + delim_name + "-separated fields, header has " +
                  std::to_string(t.header.size()));
    t.rows.push_back({line_no, std::move(cells)});
  }
  if (t.header.empty()) throw Error(origin + ": empty file (no header line)");
  return t;
}

double cell_number(const TextRow& row, size_t col, const std::string& column_name, const std::string& origin,
                   bool allow_missing) {
  const std::string& s = row.cells.at(col);
  const std::string where = origin + ":" + std::to_string(row.line);
  if (s.empty() || s == "nan" || s == "NaN" || s == "NA") {
    if (allow_missing) return std::numeric_limits<double>::quiet_NaN();
    throw Error(where + ": missing value in column '" + column_name + "'");
  }
  const char* b = s.c_str();
  char* end = nullptr;
  double v = std::strtod(b, &end);
  if (end == b || end != b + s.size()) throw Error(where + ": '" + s + "' in column '" + column_name + "' is not a number");
  if (std::isnan(v) && !allow_missing) throw Error(where + ": missing value in column '" + column_name + "'");
  if (std::isinf(v)) throw Error(where + ": '" + s + "' in column '" + column_name + "' is not a finite number");
  return v;
}

}  // namespace phasmid::fit
