#include "fit/kinematic_data.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "common/error.hpp"
#include "io/text_file.hpp"
#include "fit/text_table.hpp"

namespace phasmid::fit {
namespace {
void check_times(const KinematicData& d, const std::vector<size_t>& lines, const std::string& origin) {
  for (size_t k = 0; k < d.time_ms.size(); ++k) {
    if (!std::isfinite(d.time_ms[k]))
      throw Error(origin + ":" + std::to_string(lines[k]) + ": time is not a finite number");
    if (d.time_ms[k] < 0) throw Error(origin + ":" + std::to_string(lines[k]) + ": negative time " + std::to_string(d.time_ms[k]) + " ms");
    if (k > 0 && !(d.time_ms[k] > d.time_ms[k - 1]))
      throw Error(origin + ":" + std::to_string(lines[k]) + ": times must increase strictly (" +
                  std::to_string(d.time_ms[k]) + " ms after " + std::to_string(d.time_ms[k - 1]) + " ms)");
  }
  if (d.time_ms.empty()) throw Error(origin + ": no data rows");
}
}  // namespace

bool is_channel_name(const std::string& s) {
  static const std::set<std::string> legs = {"front", "middle", "hind", "L1", "L2", "L3", "R1", "R2", "R3"};
  static const std::set<std::string> joints = {"thc", "ctr", "fti"};
  auto dot = s.find('.');
  if (dot == std::string::npos) return false;
  return legs.count(s.substr(0, dot)) && joints.count(s.substr(dot + 1));
}

KinematicData parse_kinematic_csv(const std::string& text, const std::string& origin) {
  TextTable t = parse_text_table(text, origin, ',');
  const std::string hl = origin + ":" + std::to_string(t.header_line);
  size_t tcol = t.header.size();
  KinematicData d;
  d.source = origin;
  std::vector<size_t> acols;
  for (size_t c = 0; c < t.header.size(); ++c) {
    if (t.header[c] == "time_ms") {
      tcol = c;
    } else if (is_channel_name(t.header[c])) {
      acols.push_back(c);
      d.channels.push_back(t.header[c]);
    } else {
      throw Error(hl + ": column '" + t.header[c] + "' is neither time_ms nor an angle <leg>.<joint> (e.g. middle.fti)");
    }
  }
  if (tcol == t.header.size()) throw Error(hl + ": no time_ms column");
  if (acols.empty()) throw Error(hl + ": no angle columns (<leg>.<joint>, degrees)");
  d.angles_deg.assign(acols.size(), {});
  std::vector<size_t> lines;
  for (const auto& row : t.rows) {
    d.time_ms.push_back(cell_number(row, tcol, "time_ms", origin));
    lines.push_back(row.line);
    for (size_t a = 0; a < acols.size(); ++a)
      d.angles_deg[a].push_back(cell_number(row, acols[a], t.header[acols[a]], origin, true));
  }
  check_times(d, lines, origin);
  return d;
}

KinematicData read_kinematic_csv(const std::string& path) { return parse_kinematic_csv(io::read_text_file(path, "kinematic data"), path); }

KinematicData parse_anipose_csv(const std::string& text, const std::string& origin, const AniposeOptions& o) {
  if (!(o.frame_rate_hz > 0)) throw Error(origin + ": Anipose data need frame_rate_hz > 0 in the config");
  if (o.columns.empty()) throw Error(origin + ": Anipose data need a column mapping (columns = { COLUMN = \"<leg>.<joint>\" })");
  TextTable t = parse_text_table(text, origin, ',');
  const std::string hl = origin + ":" + std::to_string(t.header_line);
  size_t fcol = t.header.size();
  for (size_t c = 0; c < t.header.size(); ++c)
    if (t.header[c] == "fnum") fcol = c;
  if (fcol == t.header.size()) throw Error(hl + ": no fnum column (Anipose angle CSV)");
  KinematicData d;
  d.source = origin;
  std::vector<size_t> acols;
  for (auto& [column, channel] : o.columns) {
    if (!is_channel_name(channel)) throw Error(origin + ": mapping of column '" + column + "' to '" + channel + "' is not <leg>.<joint>");
    size_t c = 0;
    while (c < t.header.size() && t.header[c] != column) ++c;
    if (c == t.header.size()) throw Error(hl + ": mapped column '" + column + "' not in the header");
    acols.push_back(c);
    d.channels.push_back(channel);
  }
  d.angles_deg.assign(acols.size(), {});
  std::vector<size_t> lines;
  for (const auto& row : t.rows) {
    double f = cell_number(row, fcol, "fnum", origin);
    if (f < 0 || f != std::floor(f))
      throw Error(origin + ":" + std::to_string(row.line) + ": fnum " + row.cells[fcol] + " is not a frame number (an integer >= 0)");
    d.time_ms.push_back((f - o.fnum_offset) / o.frame_rate_hz * 1000.0);
    lines.push_back(row.line);
    for (size_t a = 0; a < acols.size(); ++a)
      d.angles_deg[a].push_back(cell_number(row, acols[a], t.header[acols[a]], origin, true));
  }
  check_times(d, lines, origin);
  return d;
}

KinematicData read_anipose_csv(const std::string& path, const AniposeOptions& o) {
  return parse_anipose_csv(io::read_text_file(path, "Anipose angles"), path, o);
}

std::string format_kinematic_csv(const KinematicData& d, const std::string& comment) {
  std::ostringstream os;
  os.precision(10);
  if (!comment.empty()) {
    std::istringstream cs(comment);
    for (std::string l; std::getline(cs, l);) os << "# " << l << "\n";
  }
  os << "time_ms";
  for (auto& c : d.channels) os << "," << c;
  os << "\n";
  for (size_t k = 0; k < d.time_ms.size(); ++k) {
    os << d.time_ms[k];
    for (auto& a : d.angles_deg) {
      os << ",";
      if (std::isfinite(a[k])) os << a[k];
    }
    os << "\n";
  }
  return os.str();
}

}  // namespace phasmid::fit
