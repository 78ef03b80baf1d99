#include "fit/kinematic_data.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "common/error.hpp"
#include "io/text_file.hpp"
#include "fit/locomotion_mat.hpp"
#include "io/h5_file.hpp"
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

namespace {
// A `contact.<leg>` column's leg, or "" when the column is no contact column.
std::string contact_leg(const std::string& column) {
  const std::string prefix = "contact.";
  if (column.compare(0, prefix.size(), prefix) != 0) return "";
  const std::string leg = column.substr(prefix.size());
  return is_channel_name(leg + ".fti") ? leg : "";
}

// The stances of one 0/1 contact column (docs/recordings.md).
std::vector<features::Stance> contact_stances(const TextTable& t, size_t col, const std::vector<double>& time_ms,
                                              const std::string& origin) {
  std::vector<double> c;
  for (const auto& row : t.rows) {
    const double v = cell_number(row, col, t.header[col], origin, true);
    if (std::isfinite(v) && v != 0 && v != 1)
      throw Error(origin + ":" + std::to_string(row.line) + ": '" + row.cells[col] + "' in column '" + t.header[col] +
                  "' is not 0 or 1 (ground contact)");
    if (!std::isfinite(v)) throw Error(origin + ":" + std::to_string(row.line) + ": column '" + t.header[col] + "' has no value (0 or 1)");
    c.push_back(v);
  }
  return features::stances_from_contact(time_ms, c);
}
}  // namespace

KinematicData parse_kinematic_csv(const std::string& text, const std::string& origin, double frame_rate_hz) {
  TextTable t = parse_text_table(text, origin, ',');
  const std::string hl = origin + ":" + std::to_string(t.header_line);
  size_t tcol = t.header.size(), fcol = t.header.size();
  KinematicData d;
  d.source = origin;
  std::vector<size_t> acols;
  std::vector<std::pair<std::string, size_t>> ccols;
  for (size_t c = 0; c < t.header.size(); ++c) {
    const std::string& h = t.header[c];
    if (h == "time_ms") {
      tcol = c;
    } else if (h == "frame") {
      fcol = c;
    } else if (is_channel_name(h)) {
      acols.push_back(c);
      d.channels.push_back(h);
    } else if (!contact_leg(h).empty()) {
      ccols.emplace_back(contact_leg(h), c);
    } else {
      throw Error(hl + ": column '" + h + "' is neither time_ms, frame, an angle <leg>.<joint> (e.g. middle.fti) nor contact.<leg>");
    }
  }
  if (tcol == t.header.size() && fcol == t.header.size()) throw Error(hl + ": no time_ms column (or frame column with a frame rate)");
  if (tcol == t.header.size() && !(frame_rate_hz > 0))
    throw Error(hl + ": a frame column needs a frame rate (frame_rate_hz in [fit.data], --frame-rate on the command line)");
  if (acols.empty()) throw Error(hl + ": no angle columns (<leg>.<joint>, degrees)");
  d.angles_deg.assign(acols.size(), {});
  std::vector<size_t> lines;
  for (const auto& row : t.rows) {
    if (tcol != t.header.size()) {
      d.time_ms.push_back(cell_number(row, tcol, "time_ms", origin));
    } else {
      const double f = cell_number(row, fcol, "frame", origin);
      if (f < 0 || f != std::floor(f))
        throw Error(origin + ":" + std::to_string(row.line) + ": frame " + row.cells[fcol] + " is not a frame number (an integer >= 0)");
      d.time_ms.push_back(f / frame_rate_hz * 1000.0);
    }
    lines.push_back(row.line);
    for (size_t a = 0; a < acols.size(); ++a)
      d.angles_deg[a].push_back(cell_number(row, acols[a], t.header[acols[a]], origin, true));
  }
  check_times(d, lines, origin);
  for (const auto& [leg, col] : ccols) d.stances[leg] = contact_stances(t, col, d.time_ms, origin);
  return d;
}

KinematicData read_kinematic_csv(const std::string& path, double frame_rate_hz) {
  return parse_kinematic_csv(io::read_text_file(path, "kinematic data"), path, frame_rate_hz);
}

KinematicData read_run_angles(const std::string& path) {
  io::H5Reader in(path);
  if (!in.is_group("/trajectory/angles")) throw Error(path + ": no /trajectory/angles (not a run file of phasmid simulate or fit)");
  KinematicData d;
  d.source = path;
  d.time_ms = in.read_doubles("/trajectory/time");
  for (const std::string& leg : in.children("/trajectory/angles"))
    for (const std::string& joint : in.children("/trajectory/angles/" + leg)) {
      d.channels.push_back(leg + "." + joint);
      d.angles_deg.push_back(in.read_doubles("/trajectory/angles/" + leg + "/" + joint));
      if (d.angles_deg.back().size() != d.time_ms.size())
        throw Error(path + ": /trajectory/angles/" + leg + "/" + joint + " has " + std::to_string(d.angles_deg.back().size()) +
                    " samples, /trajectory/time " + std::to_string(d.time_ms.size()));
    }
  if (in.is_group("/trajectory/footfall"))
    for (const std::string& leg : in.children("/trajectory/footfall")) {
      std::vector<double> contact = in.read_doubles("/trajectory/footfall/" + leg);
      if (contact.size() != d.time_ms.size()) throw Error(path + ": /trajectory/footfall/" + leg + " has the wrong length");
      for (double& c : contact) c = c == 0 ? 1 : (c == 1 ? 0 : std::nan(""));
      d.stances[leg] = features::stances_from_contact(d.time_ms, contact);
    }
  return d;
}

KinematicData read_recording(const std::string& path, double frame_rate_hz, const std::vector<std::string>& legs) {
  auto ends_with = [&](const std::string& ext) {
    return path.size() > ext.size() && path.compare(path.size() - ext.size(), ext.size(), ext) == 0;
  };
  if (ends_with(".mat")) return read_locomotion_mat(path, legs);
  if (ends_with(".h5")) return read_run_angles(path);
  return read_kinematic_csv(path, frame_rate_hz);
}

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
  for (auto& [leg, s] : d.stances) os << ",contact." << leg;
  os << "\n";
  for (size_t k = 0; k < d.time_ms.size(); ++k) {
    const double t = d.time_ms[k];
    os << t;
    for (auto& a : d.angles_deg) {
      os << ",";
      if (std::isfinite(a[k])) os << a[k];
    }
    for (auto& [leg, stances] : d.stances) {  // a censored touchdown (lift-off) is before (after) the samples
      bool on = false;
      for (const auto& s : stances)
        on = on || ((!std::isfinite(s.touchdown_ms) || s.touchdown_ms <= t) && (!std::isfinite(s.liftoff_ms) || t < s.liftoff_ms));
      os << (on ? ",1" : ",0");
    }
    os << "\n";
  }
  return os.str();
}

}  // namespace phasmid::fit
