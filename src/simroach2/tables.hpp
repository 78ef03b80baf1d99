#pragma once
// The SimRoach2 supplement's Tables 1-5 (datasets/simroach2/*.csv), found at run time in the
// binary (embedded at build time) or, failing that, under PHASMID_SOURCE_DIR.
#include <map>
#include <string>
#include <vector>

namespace phasmid::simroach2 {

// One CSV: '#' comment lines, a header, then rows kept as the printed text, so that the
// precision of each printed number is known.
struct Table {
  std::string origin;  // "datasets/simroach2/<file>" (embedded) or a file path
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  std::size_t column(const std::string& name) const;  // throws phasmid::Error naming origin
  double number(std::size_t row, const std::string& name) const;
  const std::string& text(std::size_t row, const std::string& name) const;
};

Table parse_table(const std::string& text, const std::string& origin);
// file: e.g. "table3_muscle_activation.csv"
Table load_table(const std::string& file);

// Decimal places of a printed number ("1.00" -> 2, "-143.0" -> 1, "10" -> 0).
int printed_decimals(const std::string& number);

}  // namespace phasmid::simroach2
