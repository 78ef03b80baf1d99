#pragma once
// Delimited text tables (CSV, TSV) with line numbers kept for one-line "file:line: ..." errors.
#include <string>
#include <vector>

namespace phasmid::fit {

struct TextRow {
  size_t line;                     // 1-based line in the file
  std::vector<std::string> cells;  // trimmed
};

struct TextTable {
  size_t header_line = 0;
  std::vector<std::string> header;
  std::vector<TextRow> rows;
};

// Blank lines and lines starting with '#' are skipped; the first other line is the header.
// Double-quoted cells may contain the delimiter. Every row must have as many cells as the
// header, else Error("origin:line: ...").
TextTable parse_text_table(const std::string& text, const std::string& origin, char delimiter);

// The cell as a number; "" / "nan" / "NaN" give NaN when allow_missing, else an error naming origin:line.
double cell_number(const TextRow& row, size_t col, const std::string& column_name, const std::string& origin,
                   bool allow_missing = false);

}  // namespace phasmid::fit
