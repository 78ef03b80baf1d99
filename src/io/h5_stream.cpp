#include "io/h5_stream.hpp"

#include <algorithm>

#include "common/error.hpp"

namespace phasmid::io {

AppendedDataset::AppendedDataset(H5Writer& w, const std::string& path, const std::string& units)
    : w_(w), path_(path) {
  const auto slash = path.rfind('/');
  w.ensure_group(slash == 0 ? "/" : path.substr(0, slash));
  const hsize_t zero = 0, unlimited = H5S_UNLIMITED, chunk = kStreamBlock;
  hid_t space = H5Screate_simple(1, &zero, &unlimited);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, 1, &chunk);
  // No chunk cache (HDF5 keeps up to 1 MiB per open dataset by default, and a run has one
  // dataset per state): append() writes whole chunks but the last, and reads go by block.
  hid_t dapl = H5Pcreate(H5P_DATASET_ACCESS);
  H5Pset_chunk_cache(dapl, H5D_CHUNK_CACHE_NSLOTS_DEFAULT, 0, H5D_CHUNK_CACHE_W0_DEFAULT);
  ds_ = H5Dcreate2(w.id(), path.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, dapl);
  H5Pclose(dapl);
  H5Pclose(dcpl);
  H5Sclose(space);
  if (ds_ < 0) throw Error("HDF5: cannot create dataset " + path + " in " + w.final_path() + ".tmp");
  w.set_attribute(path, "units", units);
}

AppendedDataset::~AppendedDataset() {
  if (ds_ >= 0) H5Dclose(ds_);
}

void AppendedDataset::append(const double* values, size_t n) {
  if (n == 0) return;
  const hsize_t start = size_, count = n, grown = size_ + n;
  herr_t st = H5Dset_extent(ds_, &grown);
  hid_t file_space = st < 0 ? -1 : H5Dget_space(ds_);
  hid_t mem_space = H5Screate_simple(1, &count, nullptr);
  if (file_space >= 0) {
    st = H5Sselect_hyperslab(file_space, H5S_SELECT_SET, &start, nullptr, &count, nullptr);
    if (st >= 0) st = H5Dwrite(ds_, H5T_NATIVE_DOUBLE, mem_space, file_space, H5P_DEFAULT, values);
    H5Sclose(file_space);
  }
  H5Sclose(mem_space);
  if (st < 0 || file_space < 0) throw Error("HDF5: cannot write " + path_ + " to " + w_.final_path() + ".tmp");
  size_ = grown;
}

BlockCursor::BlockCursor(hid_t ds, const std::string& what) : ds_(ds), what_(what) {
  hid_t space = H5Dget_space(ds);
  if (space < 0 || H5Sget_simple_extent_ndims(space) != 1) {
    if (space >= 0) H5Sclose(space);
    throw Error("HDF5: " + what + " is not a 1-D dataset");
  }
  H5Sget_simple_extent_dims(space, &size_, nullptr);
  H5Sclose(space);
}

double BlockCursor::at(hsize_t i) {
  if (i >= base_ && i < base_ + window_.size()) return window_[i - base_];
  if (i >= size_ || i < base_) throw Error("internal: " + what_ + " read at " + std::to_string(i) + " out of order");
  base_ = i > 0 ? i - 1 : 0;  // one value back: interpolation reads i - 1 after i
  const hsize_t count = std::min<hsize_t>(kStreamBlock, size_ - base_);
  window_.resize(count);
  hid_t file_space = H5Dget_space(ds_);
  hid_t mem_space = H5Screate_simple(1, &count, nullptr);
  herr_t st = H5Sselect_hyperslab(file_space, H5S_SELECT_SET, &base_, nullptr, &count, nullptr);
  if (st >= 0) st = H5Dread(ds_, H5T_NATIVE_DOUBLE, mem_space, file_space, H5P_DEFAULT, window_.data());
  H5Sclose(mem_space);
  H5Sclose(file_space);
  if (st < 0) throw Error("HDF5: cannot read " + what_);
  return window_[i - base_];
}

std::vector<double> read_strided(const H5Reader& r, const std::string& path, hsize_t stride) {
  const std::vector<hsize_t> dims = r.dims(path);
  if (dims.empty() || dims.size() > 2 || stride == 0)
    throw Error(r.path() + ": dataset " + path + " is not a series of rank 1 or 2");
  const hsize_t cols = dims.size() == 2 ? dims[1] : 1, rows = (dims[0] + stride - 1) / stride;
  const hsize_t start[2] = {0, 0}, step[2] = {stride, 1}, count[2] = {rows, cols};
  std::vector<double> out(static_cast<size_t>(rows * cols));
  hid_t ds = H5Dopen2(r.id(), path.c_str(), H5P_DEFAULT);
  hid_t file_space = H5Dget_space(ds);
  hid_t mem_space = H5Screate_simple(static_cast<int>(dims.size()), count, nullptr);
  herr_t st = H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, step, count, nullptr);
  if (st >= 0 && rows > 0) st = H5Dread(ds, H5T_NATIVE_DOUBLE, mem_space, file_space, H5P_DEFAULT, out.data());
  H5Sclose(mem_space);
  H5Sclose(file_space);
  H5Dclose(ds);
  if (st < 0) throw Error(r.path() + ": cannot read " + path);
  return out;
}

}  // namespace phasmid::io
