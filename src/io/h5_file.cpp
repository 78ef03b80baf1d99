#include "io/h5_file.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "common/error.hpp"
#include "io/h5_heap_check.hpp"
#include "io/output_lock.hpp"
#include "io/output_path.hpp"
#include "build_info.hpp"

namespace phasmid::io {
namespace {

// HDF5 closes what is still open when the process exits; a file whose close failed (a full
// disk) is still open and that second close crashes inside HDF5, after our error message. Files
// are closed by H5Writer and H5Reader themselves, so the exit-time close is not needed.
struct SilenceHdf5 {
  SilenceHdf5() {
    H5dont_atexit();  // before any other HDF5 call
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
};
const SilenceHdf5 silence_hdf5_once;  // we report errors ourselves, in one line

void check(herr_t status, const std::string& what) {
  if (status < 0) throw Error("HDF5: " + what);
}

std::string parent_of(const std::string& path) {
  auto pos = path.rfind('/');
  return pos == 0 || pos == std::string::npos ? "/" : path.substr(0, pos);
}

hid_t open_object(hid_t file, const std::string& path) {
  hid_t obj = H5Oopen(file, path.c_str(), H5P_DEFAULT);
  if (obj < 0) throw Error("HDF5: no object " + path);
  return obj;
}

std::string now_iso8601() {
  std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

}  // namespace

H5Writer::H5Writer(const std::string& path) : path_(path), tmp_path_(path + ".tmp") {
  check_output_path(path);
  lock_ = std::make_unique<HeldOutputLock>(path);  // before "<path>.tmp" is truncated
  // HDF5's own flock() is left out: the output lock already excludes other writers, and where
  // flock() is emulated by record locks (NFS) it would collide with that lock.
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl >= 0) H5Pset_file_locking(fapl, false, true);
  file_ = H5Fcreate(tmp_path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl >= 0 ? fapl : H5P_DEFAULT);
  if (fapl >= 0) H5Pclose(fapl);
  if (file_ < 0) throw Error("cannot create HDF5 file " + tmp_path_);
}

H5Writer::~H5Writer() {
  if (file_ >= 0) H5Fclose(file_);
  if (!committed_) std::remove(tmp_path_.c_str());  // still under the lock, released after
}

void H5Writer::ensure_group(const std::string& path) {
  if (path.empty() || path == "/") return;
  std::string partial;
  size_t start = 1;
  while (start <= path.size()) {
    size_t end = path.find('/', start);
    if (end == std::string::npos) end = path.size();
    partial += "/" + path.substr(start, end - start);
    if (H5Lexists(file_, partial.c_str(), H5P_DEFAULT) <= 0) {
      hid_t g = H5Gcreate2(file_, partial.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      if (g < 0) throw Error("HDF5: cannot create group " + partial);
      H5Gclose(g);
    }
    start = end + 1;
  }
}

namespace {
template <class T>
void write_numeric(H5Writer& w, hid_t file, const std::string& path, const std::vector<T>& data,
                   hid_t mem_type, hid_t file_type, const std::string& units, std::vector<hsize_t> dims) {
  if (dims.empty()) dims = {static_cast<hsize_t>(data.size())};
  hsize_t total = 1;
  for (auto d : dims) total *= d;
  if (total != data.size()) throw Error("HDF5: shape mismatch writing " + path);
  w.ensure_group(parent_of(path));
  hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  hid_t ds = H5Dcreate2(file, path.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (ds < 0) {
    H5Sclose(space);
    throw Error("HDF5: cannot create dataset " + path);
  }
  herr_t st = data.empty() ? 0 : H5Dwrite(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data());
  H5Dclose(ds);
  H5Sclose(space);
  check(st, "cannot write " + path + " to " + w.final_path() + ".tmp");
  w.set_attribute(path, "units", units);
}
}  // namespace

void H5Writer::write(const std::string& path, const std::vector<double>& data, const std::string& units,
                     std::vector<hsize_t> dims) {
  write_numeric(*this, file_, path, data, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, units, std::move(dims));
}

void H5Writer::write(const std::string& path, const std::vector<std::int64_t>& data, const std::string& units,
                     std::vector<hsize_t> dims) {
  write_numeric(*this, file_, path, data, H5T_NATIVE_INT64, H5T_STD_I64LE, units, std::move(dims));
}

void H5Writer::write(const std::string& path, const std::vector<std::string>& data) {
  ensure_group(parent_of(path));
  std::vector<const char*> ptrs;
  for (auto& s : data) ptrs.push_back(s.c_str());
  hsize_t n = data.size();
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  hid_t space = H5Screate_simple(1, &n, nullptr);
  hid_t ds = H5Dcreate2(file_, path.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  herr_t st = ds < 0 ? -1 : (n ? H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()) : 0);
  if (ds >= 0) H5Dclose(ds);
  H5Sclose(space);
  H5Tclose(type);
  check(st, "cannot write " + path + " to " + tmp_path_);
  set_attribute(path, "units", "1");
}

void H5Writer::write_scalar(const std::string& path, const double value, const std::string& units) {
  ensure_group(parent_of(path));
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t ds = H5Dcreate2(file_, path.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  herr_t st = ds < 0 ? -1 : H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value);
  if (ds >= 0) H5Dclose(ds);
  H5Sclose(space);
  check(st, "cannot write " + path + " to " + tmp_path_);
  set_attribute(path, "units", units);
}

void H5Writer::write_string(const std::string& path, const std::string& value) {
  ensure_group(parent_of(path));
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  hid_t space = H5Screate(H5S_SCALAR);
  const char* p = value.c_str();
  hid_t ds = H5Dcreate2(file_, path.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  herr_t st = ds < 0 ? -1 : H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, &p);
  if (ds >= 0) H5Dclose(ds);
  H5Sclose(space);
  H5Tclose(type);
  check(st, "cannot write " + path + " to " + tmp_path_);
  set_attribute(path, "units", "1");
}

void H5Writer::set_attribute(const std::string& object_path, const std::string& name, const std::string& value) {
  hid_t obj = open_object(file_, object_path);
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t attr = H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
  const char* p = value.c_str();
  herr_t st = attr < 0 ? -1 : H5Awrite(attr, type, &p);
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
  H5Oclose(obj);
  check(st, "cannot write attribute " + name + " on " + object_path + " to " + tmp_path_);
}

void H5Writer::set_attribute(const std::string& object_path, const std::string& name, double value) {
  hid_t obj = open_object(file_, object_path);
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t attr = H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  herr_t st = attr < 0 ? -1 : H5Awrite(attr, H5T_NATIVE_DOUBLE, &value);
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  H5Oclose(obj);
  check(st, "cannot write attribute " + name + " on " + object_path + " to " + tmp_path_);
}

void H5Writer::write_run_info(const RunInfo& info) {
  set_attribute("/", "phasmid_version", std::string(PHASMID_VERSION));
  set_attribute("/", "config", info.config_text);
  set_attribute("/", "command", info.command);
  set_attribute("/", "created", now_iso8601());
}

void H5Writer::commit() {
  if (committed_) return;
  check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flush failed for " + tmp_path_);
  const herr_t closed = H5Fclose(file_);
  file_ = -1;
  // The close writes the last metadata: a file that failed it is not renamed into place.
  check(closed, "cannot close " + tmp_path_);
  // A lock held by the caller stays the caller's for its next write (gsa: the sweep, then the
  // analysis); a writer's own lock is released with the writer.
  lock_->get().publish(!lock_->owned());
  committed_ = true;
}

H5Reader::H5Reader(const std::string& path) : path_(path) {
  if (!std::filesystem::exists(path)) throw Error(path + ": no such file");
  if (!std::filesystem::is_regular_file(path)) throw Error(path + ": not a regular file");  // a fifo would block
  check_global_heaps(path);  // before HDF5 sees the file: it would loop on some damaged heaps
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file_ < 0) throw Error(path + ": not an HDF5 file");
}

H5Reader::~H5Reader() {
  if (file_ >= 0) H5Fclose(file_);
}

bool H5Reader::exists(const std::string& path) const {
  if (path == "/") return true;
  // Check each prefix: H5Lexists fails on missing intermediate groups.
  size_t pos = 0;
  while ((pos = path.find('/', pos + 1)) != std::string::npos) {
    if (H5Lexists(file_, path.substr(0, pos).c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return H5Lexists(file_, path.c_str(), H5P_DEFAULT) > 0;
}

bool H5Reader::is_group(const std::string& path) const {
  if (!exists(path)) return false;
  H5O_info_t info;
  if (H5Oget_info_by_name2(file_, path.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0) return false;
  return info.type == H5O_TYPE_GROUP;
}

std::vector<hsize_t> H5Reader::dims(const std::string& path) const {
  hid_t ds = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
  if (ds < 0) throw Error(path_ + ": no dataset " + path);
  hid_t space = H5Dget_space(ds);
  int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> d(std::max(rank, 0));
  if (rank > 0) H5Sget_simple_extent_dims(space, d.data(), nullptr);
  H5Sclose(space);
  H5Dclose(ds);
  return d;
}

// A dataset may declare any extent in a few bytes (unallocated or compressed storage): refuse
// one whose values could not have come from a file of this size before allocating for them.
void H5Reader::check_extent(hid_t ds, hid_t space, const std::string& path) const {
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  hsize_t file_bytes = 0;
  H5Fget_filesize(file_, &file_bytes);
  const double bytes = static_cast<double>(n) * 8.0;
  const double limit = std::max(kMinReadLimitBytes, kMaxExpansion * static_cast<double>(file_bytes));
  if (n < 0 || bytes > limit) {
    H5Sclose(space);
    H5Dclose(ds);
    throw Error(path_ + ": dataset " + path + " declares " + std::to_string(n) + " values, more than a " +
                std::to_string(file_bytes) + "-byte file holds");
  }
}

std::vector<double> H5Reader::read_doubles(const std::string& path) const {
  hid_t ds = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
  if (ds < 0) throw Error(path_ + ": no dataset " + path);
  hid_t space = H5Dget_space(ds);
  check_extent(ds, space, path);
  hssize_t n = H5Sget_simple_extent_npoints(space);
  std::vector<double> out(static_cast<size_t>(n));
  herr_t st = n ? H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) : 0;
  H5Sclose(space);
  H5Dclose(ds);
  check(st, "cannot read " + path + " from " + path_);
  return out;
}

std::vector<std::string> H5Reader::read_strings(const std::string& path) const {
  hid_t ds = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
  if (ds < 0) throw Error(path_ + ": no dataset " + path);
  hid_t space = H5Dget_space(ds);
  check_extent(ds, space, path);
  hssize_t n = H5Sget_simple_extent_npoints(space);
  try {
    check_string_descriptors(file_, ds, static_cast<hsize_t>(n), path_, path);  // HDF5 allocates what they declare
  } catch (...) {
    H5Sclose(space);
    H5Dclose(ds);
    throw;
  }
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  std::vector<char*> raw(static_cast<size_t>(n), nullptr);
  herr_t st = n ? H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()) : 0;
  std::vector<std::string> out;
  for (char* p : raw) out.emplace_back(p ? p : "");
  if (n && st >= 0) H5Dvlen_reclaim(type, space, H5P_DEFAULT, raw.data());
  H5Tclose(type);
  H5Sclose(space);
  H5Dclose(ds);
  check(st, "cannot read " + path + " from " + path_);
  return out;
}

// The attribute `name` of the object at `object_path` (an error naming both if it is missing);
// the caller closes the attribute, then the object.
std::pair<hid_t, hid_t> H5Reader::open_attribute(const std::string& object_path, const std::string& name) const {
  hid_t obj = open_object(file_, object_path);
  if (H5Aexists(obj, name.c_str()) <= 0) {
    H5Oclose(obj);
    throw Error(path_ + ": no attribute " + name + " on " + object_path);
  }
  return {obj, H5Aopen(obj, name.c_str(), H5P_DEFAULT)};
}

std::string H5Reader::read_string_attribute(const std::string& object_path, const std::string& name) const {
  auto [obj, attr] = open_attribute(object_path, name);
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  char* p = nullptr;
  herr_t st = H5Aread(attr, type, &p);
  std::string out = p ? p : "";
  if (st >= 0 && p) H5free_memory(p);
  H5Tclose(type);
  H5Aclose(attr);
  H5Oclose(obj);
  check(st, "cannot read attribute " + name);
  return out;
}

double H5Reader::read_double_attribute(const std::string& object_path, const std::string& name) const {
  auto [obj, attr] = open_attribute(object_path, name);
  double value = 0.0;
  herr_t st = H5Aread(attr, H5T_NATIVE_DOUBLE, &value);
  H5Aclose(attr);
  H5Oclose(obj);
  check(st, "cannot read attribute " + name);
  return value;
}

bool H5Reader::has_attribute(const std::string& object_path, const std::string& name) const {
  hid_t obj = open_object(file_, object_path);
  const htri_t e = H5Aexists(obj, name.c_str());
  H5Oclose(obj);
  return e > 0;
}

static herr_t collect_link_name(hid_t, const char* name, const H5L_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->push_back(name);
  return 0;
}

std::vector<std::string> H5Reader::children(const std::string& group_path) const {
  std::vector<std::string> names;
  hid_t g = H5Gopen2(file_, group_path.c_str(), H5P_DEFAULT);
  if (g < 0) throw Error(path_ + ": no group " + group_path);
  H5Literate(g, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_link_name, &names);
  H5Gclose(g);
  return names;
}

}  // namespace phasmid::io
