#include "sweep/sweep_store.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "io/trajectory_writer.hpp"
#include "sweep/ranges.hpp"
#include "sweep/sweep_runner.hpp"

namespace phasmid::sweep {
namespace {
constexpr const char* kMagic = "phasmid-sweep-journal 2";  // 2: the spec in the header

std::string hex64(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, v);
  return buf;
}

std::string hexfloat(double v) {
  if (std::isnan(v)) return "nan";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

bool parse_double(const std::string& s, double& out) {
  if (s == "nan") {
    out = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end && *end == '\0' && end != s.c_str();
}

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void write_all(int fd, const std::string& s, const std::string& path) {
  const char* p = s.data();
  size_t left = s.size();
  while (left > 0) {
    ssize_t w = ::write(fd, p, left);
    if (w < 0) {
      if (errno == EINTR) continue;
      throw Error(path + ": cannot write journal: " + std::strerror(errno));
    }
    p += w;
    left -= static_cast<size_t>(w);
  }
}

// One line: the spec as a JSON string (ensure_ascii: its line breaks and any byte escaped).
std::string header_line(std::uint64_t fingerprint, std::size_t n_points, const std::string& spec) {
  return std::string(kMagic) + " fingerprint=" + hex64(fingerprint) + " n_points=" + std::to_string(n_points) +
         " spec=" + nlohmann::json(spec).dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
}

// Why a journal's header is not this sweep's: the first spec key that differs, else the design.
std::string header_mismatch(const std::string& header, const std::string& spec) {
  const std::string what = "journal belongs to a different sweep";
  const std::string tail = "; delete it to start over";
  const auto at = header.find(" spec=");
  std::string old;
  try {
    if (at != std::string::npos) old = nlohmann::json::parse(header.substr(at + 6)).get<std::string>();
  } catch (const std::exception&) {
    return what + " (its header is damaged)" + tail;
  }
  if (at == std::string::npos) return what + " (its header has no spec)" + tail;
  const std::string diff = spec_difference(old, spec, "in the journal");
  if (!diff.empty()) return what + ": the config differs from the one it was started with (" + diff + ")" + tail;
  return what + " (the same config, other design points or point count: another phasmid version?)" + tail;
}

// "key = value" lines of a spec, in order.
std::vector<std::pair<std::string, std::string>> spec_lines(const std::string& spec) {
  std::vector<std::pair<std::string, std::string>> out;
  for (std::size_t at = 0, end; at < spec.size(); at = end + 1) {
    end = spec.find('\n', at);
    if (end == std::string::npos) end = spec.size();
    const std::string line = spec.substr(at, end - at);
    const auto eq = line.find(" = ");
    if (eq != std::string::npos) out.emplace_back(line.substr(0, eq), line.substr(eq + 3));
  }
  return out;
}
}  // namespace

std::uint64_t fnv1a(const std::string& bytes, std::uint64_t h) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

std::uint64_t sweep_fingerprint(const std::string& resume_spec, const SweepSpec& spec) {
  std::string s = resume_spec;
  s += "\n#design " + spec.design_name + " seed " + std::to_string(spec.seed);
  s += "\n#t " + hexfloat(spec.t_end_ms) + " " + hexfloat(spec.discard_ms);
  for (auto& p : spec.parameters) s += "\n#p " + p.name;
  for (auto& o : spec.options) {
    s += "\n#o " + o.name;
    for (auto& l : o.labels) s += " " + std::to_string(l.size()) + ":" + l;
  }
  s += "\n#x";
  for (double x : spec.points) s += " " + hexfloat(x);
  return fnv1a(s);
}

std::string spec_difference(const std::string& old_spec, const std::string& new_spec, const std::string& then) {
  const auto before = spec_lines(old_spec), now = spec_lines(new_spec);
  std::map<std::string, std::string> old_value(before.begin(), before.end()), new_value(now.begin(), now.end());
  for (auto& [key, value] : now) {
    auto it = old_value.find(key);
    if (it == old_value.end()) return key + ": not set " + then + ", " + value + " now";
    if (it->second != value) return key + ": " + it->second + " " + then + ", " + value + " now";
  }
  for (auto& [key, value] : before)
    if (!new_value.count(key)) return key + ": " + value + " " + then + ", not set now";
  return "";
}

void check_finished_sweep(const std::string& output, const SweepInputs& in) {
  io::H5Reader r(output);
  const std::string fresh = "; delete it or write to another -o to start over";
  if (!r.exists("/sweep"))
    throw Error(output + ": --resume without a journal needs a finished sweep file, and this one has no /sweep" + fresh);
  if (!r.has_attribute("/sweep", "resume_spec")) {  // an older phasmid's file: only the very same config text
    if (r.has_attribute("/", "config") && r.read_string_attribute("/", "config") == in.resolved_config) return;
    throw Error(output + ": made by an older phasmid without a resume fingerprint, with another config text" + fresh);
  }
  const std::string diff = spec_difference(r.read_string_attribute("/sweep", "resume_spec"), in.resume_spec, "in " + output);
  if (!diff.empty()) throw Error("the config differs from the one " + output + " was made with (" + diff + ")" + fresh);
  if (r.read_string_attribute("/sweep", "resume_fingerprint") != hex64(sweep_fingerprint(in.resume_spec, in.spec)))
    throw Error(output + ": its design points differ from this config's ([gsa] or [sweep] design changed)" + fresh);
}

std::string encode_record(std::size_t index, const PointResult& r) {
  nlohmann::json j;
  j["i"] = index;
  j["s"] = r.status;
  j["g"] = r.gait_class;
  nlohmann::json f = nlohmann::json::array();
  for (auto& x : r.features) f.push_back({x.name, hexfloat(x.value), x.unit});
  j["f"] = f;
  // ensure_ascii: the line stays one line of plain bytes whatever a solver message contains
  std::string payload = j.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
  return hex64(fnv1a(payload)) + " " + payload;
}

bool decode_record(const std::string& line, std::size_t& index, PointResult& r) {
  if (line.size() < 18 || line[16] != ' ') return false;
  std::string payload = line.substr(17);
  if (hex64(fnv1a(payload)) != line.substr(0, 16)) return false;
  try {
    auto j = nlohmann::json::parse(payload);
    index = j.at("i").get<std::size_t>();
    r = PointResult{};
    r.status = j.at("s").get<std::string>();
    r.gait_class = j.at("g").get<std::string>();
    for (auto& f : j.at("f")) {
      features::Feature x;
      x.name = f.at(0).get<std::string>();
      if (!parse_double(f.at(1).get<std::string>(), x.value)) return false;
      x.unit = f.at(2).get<std::string>();
      r.features.push_back(std::move(x));
    }
  } catch (const std::exception&) {
    return false;
  }
  return true;
}

Journal::Journal(const std::string& path, std::uint64_t fingerprint, std::size_t n_points, bool resume,
                 const std::string& spec)
    : path_(path) {
  namespace fs = std::filesystem;
  const std::string header = header_line(fingerprint, n_points, spec);
  if (resume && fs::exists(path)) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    if (fd_ < 0) throw Error(path + ": cannot open journal for appending: " + std::strerror(errno));
    lock_or_throw();  // before reading: a running sweep may still be appending
    auto fail = [&](const std::string& msg) {
      ::close(fd_);
      fd_ = -1;
      throw Error(path + ": " + msg);
    };
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("cannot read journal");
    std::string line;
    std::uintmax_t good_end = 0, pos = 0;
    bool first = true;
    while (std::getline(in, line)) {
      const bool complete = !in.eof();  // getline hit a newline
      pos += line.size() + (complete ? 1 : 0);
      if (first) {
        first = false;
        if (!complete || line.rfind(kMagic, 0) != 0) fail("not a phasmid sweep journal");
        if (line != header) fail(header_mismatch(line, spec));
        good_end = pos;
        continue;
      }
      std::size_t index;
      PointResult r;
      if (complete && decode_record(line, index, r) && index < n_points) {
        recovered_.emplace(index, std::move(r));  // first record of a point wins
        good_end = pos;
      } else {
        ++torn_;
        good_end = pos;  // skip the bad line but keep what follows; its point is recomputed
        if (!complete) good_end = pos - line.size();  // a torn tail is cut off before appending
      }
    }
    if (first) fail("empty sweep journal; delete it to start over");
    in.close();
    if (::ftruncate(fd_, static_cast<off_t>(good_end)) != 0) fail(std::string("cannot truncate journal: ") + std::strerror(errno));
  } else {
    auto dir = fs::path(path).parent_path();
    if (!dir.empty()) fs::create_directories(dir);
    // Lock before truncating: a sweep refused on a busy output must not empty the running one's journal.
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd_ < 0) throw Error(path + ": cannot create journal: " + std::strerror(errno));
    lock_or_throw();
    if (::ftruncate(fd_, 0) != 0) throw Error(path + ": cannot truncate journal: " + std::strerror(errno));
    write_all(fd_, header + "\n", path_);
    ::fdatasync(fd_);
  }
  last_sync_ = now_seconds();
}

void Journal::lock_or_throw() {
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd_);
    fd_ = -1;
    throw Error(path_ + ": another phasmid sweep is running on this output (journal locked)");
  }
}

Journal::~Journal() {
  if (fd_ >= 0) {
    ::fdatasync(fd_);
    ::close(fd_);
  }
}

void Journal::append(std::size_t index, const PointResult& r) { append_line(encode_record(index, r)); }

void Journal::append_line(const std::string& record) {
  const std::string line = record + "\n";
  std::lock_guard<std::mutex> lock(mu_);
  write_all(fd_, line, path_);
  double t = now_seconds();
  if (t - last_sync_ > 1.0) {  // bound what a power cut can lose; a kill loses nothing written
    ::fdatasync(fd_);
    last_sync_ = t;
  }
}

void Journal::sync() {
  std::lock_guard<std::mutex> lock(mu_);
  if (fd_ >= 0) ::fdatasync(fd_);
}

void Journal::close_and_remove() {
  std::lock_guard<std::mutex> lock(mu_);
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  std::filesystem::remove(path_);
}

void write_sweep_h5(const std::string& output, const SweepSpec& spec, const std::vector<PointResult>& results,
                    const model::ParameterSet& parameters, const std::vector<double>& base_parameters,
                    const io::RunInfo& info, const std::string& resume_spec) {
  const std::size_t n = spec.n_points, dim = spec.parameters.size();
  if (results.size() != n) throw Error("internal: sweep results incomplete");

  // Feature columns: every feature any point produced, in order of first appearance by point.
  std::vector<std::string> fnames, funits;
  std::map<std::string, std::size_t> column;
  for (auto& r : results)
    for (auto& f : r.features)
      if (column.emplace(f.name, fnames.size()).second) {
        fnames.push_back(f.name);
        funits.push_back(f.unit);
      }
  std::vector<std::vector<double>> fvalues(fnames.size(), std::vector<double>(n, std::numeric_limits<double>::quiet_NaN()));
  std::vector<std::string> status(n), gait(n);
  std::int64_t n_failed = 0;
  for (std::size_t i = 0; i < n; ++i) {
    status[i] = results[i].status;
    gait[i] = results[i].gait_class;
    if (status[i] != "ok") ++n_failed;
    for (auto& f : results[i].features) fvalues[column[f.name]][i] = f.value;
  }

  io::H5Writer w(output);
  w.write_run_info(info);
  w.ensure_group("/sweep");
  w.write("/sweep/parameter_names", spec.names());
  w.write("/sweep/parameter_units", spec.units());
  std::string units_list;
  for (auto& u : spec.units()) units_list += (units_list.empty() ? "" : ", ") + u;
  w.write("/sweep/points", spec.points, units_list, {static_cast<hsize_t>(n), static_cast<hsize_t>(dim)});
  if (!spec.options.empty()) {
    std::vector<std::string> onames;
    for (std::size_t k = 0; k < spec.options.size(); ++k) {
      onames.push_back(spec.options[k].name);
      std::vector<std::string> col(n);
      for (std::size_t i = 0; i < n; ++i) col[i] = spec.options[k].labels[spec.option_value(spec.combo_of(i), k)];
      w.write("/sweep/options/" + spec.options[k].name, col);
    }
    w.write("/sweep/option_names", onames);
  }
  w.ensure_group("/sweep/features");
  for (std::size_t k = 0; k < fnames.size(); ++k) w.write("/sweep/features/" + fnames[k], fvalues[k], funits[k]);
  w.write("/sweep/gait_class", gait);
  w.write("/sweep/status", status);
  w.set_attribute("/sweep", "design", spec.design_name);
  w.set_attribute("/sweep", "seed", static_cast<double>(spec.seed));
  w.set_attribute("/sweep", "n_points", static_cast<double>(n));
  w.set_attribute("/sweep", "n_failed", static_cast<double>(n_failed));
  w.set_attribute("/sweep", "t_end_ms", spec.t_end_ms);
  w.set_attribute("/sweep", "discard_ms", spec.discard_ms);
  w.set_attribute("/sweep", "resume_spec", resume_spec);
  w.set_attribute("/sweep", "resume_fingerprint", hex64(sweep_fingerprint(resume_spec, spec)));
  if (!spec.range_feature.empty()) {
    auto it = column.find(spec.range_feature);
    std::vector<double> none(n, std::numeric_limits<double>::quiet_NaN());
    write_ranges_h5(w, spec.range_feature, one_at_a_time_ranges(spec, it == column.end() ? none : fvalues[it->second]));
  }
  io::write_parameters(w, parameters, base_parameters);
  w.commit();
}

}  // namespace phasmid::sweep
