#pragma once
// Where sweep results live while a sweep runs and when it is done (docs/sweep.md).
//
// While running: a journal "<OUT>.journal" next to the output, one line per finished point,
// appended (one write(2) per line, under a lock) as soon as the point is done. Each line
// carries a checksum; a line torn by a kill is detected and its point recomputed. Numbers
// are stored as C99 hex floats, so a resumed sweep reproduces every bit. The header holds a
// fingerprint of the sweep (the resume spec of config/resume_spec.hpp, the points, the times)
// and the spec itself, so --resume refuses a journal that belongs to a different sweep and
// names the first key that differs. The finished file keeps both as attributes of /sweep.
// When all points are done: "<OUT>" is assembled from the results in point order through
// io::H5Writer ("<OUT>.tmp" + rename), and only then is the journal deleted. A file named
// <OUT> therefore always holds a complete sweep.
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "features/features.hpp"
#include "io/h5_file.hpp"
#include "model/parameters.hpp"
#include "sweep/sweep_spec.hpp"

namespace phasmid::sweep {

struct PointResult {
  std::string status = "ok";   // "ok" or the reason the point failed
  std::string gait_class;      // gait class label; "failed" for failed points
  std::vector<features::Feature> features;
};

// FNV-1a 64-bit hash, used for the sweep fingerprint and the per-line checksums.
std::uint64_t fnv1a(const std::string& bytes, std::uint64_t h = 0xcbf29ce484222325ull);
// resume_spec: config::resume_spec() of the sweep's config (any text in tests).
std::uint64_t sweep_fingerprint(const std::string& resume_spec, const SweepSpec& spec);

// The first thing two resume specs disagree on, "model parameter a: 7 in the journal, 0 now"
// (`then` names where `old_spec` comes from); "" when they are the same.
std::string spec_difference(const std::string& old_spec, const std::string& new_spec, const std::string& then);

// --resume of a finished file `output` (no journal): an Error naming the first difference unless
// its /sweep was made with this resume spec and design (a gsa file's /sweep too). A file of an
// older phasmid (no `resume_spec`) passes only with the very same resolved config text.
struct SweepInputs;
void check_finished_sweep(const std::string& output, const SweepInputs& in);

// One journal line (without the newline) for a point, and back. parse returns false for a
// line that is torn, corrupt or fails its checksum.
std::string encode_record(std::size_t index, const PointResult& r);
bool decode_record(const std::string& line, std::size_t& index, PointResult& r);

class Journal {
 public:
  static std::string path_for(const std::string& output) { return output + ".journal"; }
  // Creates a new journal (truncating any old one), or with `resume` reopens an existing one,
  // checks its fingerprint and point count, reads the finished points, and drops a torn tail.
  // `spec` (the resume spec) is kept in the header to name what differs on a refused resume.
  Journal(const std::string& path, std::uint64_t fingerprint, std::size_t n_points, bool resume,
          const std::string& spec = "");
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  const std::map<std::size_t, PointResult>& recovered() const { return recovered_; }
  std::size_t torn_lines() const { return torn_; }
  void append(std::size_t index, const PointResult& r);  // thread-safe; durable against kill
  void append_line(const std::string& record);            // an encode_record() line
  void sync();                                           // fdatasync
  void close_and_remove();
  const std::string& path() const { return path_; }

 private:
  void lock_or_throw();  // one sweep per journal at a time (flock, released when the process ends)
  std::string path_;
  int fd_ = -1;
  std::mutex mu_;
  std::map<std::size_t, PointResult> recovered_;
  std::size_t torn_ = 0;
  double last_sync_ = 0;
};

// Writes the /sweep group (and /parameters for the base point) to the final file, with the
// resume spec and fingerprint as /sweep attributes `resume_spec` and `resume_fingerprint`.
void write_sweep_h5(const std::string& output, const SweepSpec& spec, const std::vector<PointResult>& results,
                    const model::ParameterSet& parameters, const std::vector<double>& base_parameters,
                    const io::RunInfo& info, const std::string& resume_spec = "");

}  // namespace phasmid::sweep
