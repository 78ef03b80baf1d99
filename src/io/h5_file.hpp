#pragma once
// Thin RAII layer over the HDF5 C API with the conventions of docs/hdf5.md:
// every dataset carries a `units` attribute, intermediate groups are created on demand,
// and a file being written lives under "<path>.tmp" until commit() renames it, so an
// interrupted run never leaves a complete-looking file behind.
#include <hdf5.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace phasmid::io {

class HeldOutputLock;

// Root attributes every phasmid HDF5 file carries.
struct RunInfo {
  std::string config_text;  // the full resolved config
  std::string command;      // the command line
};

class H5Writer {
 public:
  // Writes under the output's lock (io/output_lock.hpp): the one this thread holds already, or
  // its own, taken before "<path>.tmp" is created or truncated.
  explicit H5Writer(const std::string& path);
  ~H5Writer();  // without commit(): closes and deletes the temporary file, then unlocks
  H5Writer(const H5Writer&) = delete;
  H5Writer& operator=(const H5Writer&) = delete;

  void write_run_info(const RunInfo& info);  // phasmid_version, config, command, created

  // Datasets; `dims` empty means 1-D of data.size(). Row-major for 2-D/3-D.
  void write(const std::string& path, const std::vector<double>& data, const std::string& units,
             std::vector<hsize_t> dims = {});
  void write(const std::string& path, const std::vector<std::int64_t>& data, const std::string& units,
             std::vector<hsize_t> dims = {});
  void write(const std::string& path, const std::vector<std::string>& data);
  void write_scalar(const std::string& path, double value, const std::string& units);
  void write_string(const std::string& path, const std::string& value);

  void set_attribute(const std::string& object_path, const std::string& name, const std::string& value);
  void set_attribute(const std::string& object_path, const std::string& name, double value);
  void ensure_group(const std::string& path);

  void commit();  // flush, close, rename "<path>.tmp" -> "<path>"
  hid_t id() const { return file_; }
  const std::string& final_path() const { return path_; }

 private:
  std::string path_, tmp_path_;
  std::unique_ptr<HeldOutputLock> lock_;
  hid_t file_ = -1;
  bool committed_ = false;
};

class H5Reader {
 public:
  explicit H5Reader(const std::string& path);
  ~H5Reader();
  H5Reader(const H5Reader&) = delete;
  H5Reader& operator=(const H5Reader&) = delete;

  bool exists(const std::string& path) const;
  std::vector<double> read_doubles(const std::string& path) const;
  std::vector<hsize_t> dims(const std::string& path) const;
  std::vector<std::string> read_strings(const std::string& path) const;
  std::string read_string_attribute(const std::string& object_path, const std::string& name) const;
  double read_double_attribute(const std::string& object_path, const std::string& name) const;
  bool has_attribute(const std::string& object_path, const std::string& name) const;
  std::vector<std::string> children(const std::string& group_path) const;  // member names
  bool is_group(const std::string& path) const;
  hid_t id() const { return file_; }
  const std::string& path() const { return path_; }

 private:
  std::pair<hid_t, hid_t> open_attribute(const std::string& object_path, const std::string& name) const;
  // Bounds what a read allocates by the file's size (closes space and ds before throwing).
  static constexpr double kMinReadLimitBytes = 64.0 * 1024 * 1024;
  static constexpr double kMaxExpansion = 1000.0;  // HDF5's deflate stays far below this
  void check_extent(hid_t ds, hid_t space, const std::string& path) const;
  std::string path_;
  hid_t file_ = -1;
};

}  // namespace phasmid::io
