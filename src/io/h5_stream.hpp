#pragma once
// Datasets written and read in blocks, so that neither side holds a whole trajectory:
//  - AppendedDataset: a 1-D float64 dataset of unlimited extent, chunked, that grows by
//    append(); readers see the same name, shape, type and `units` attribute as a dataset
//    written at once (H5Writer::write).
//  - BlockCursor: reads a 1-D float64 dataset forward through a window of kStreamBlock values
//    (an index may go back by one from the largest read so far, no further).
#include <hdf5.h>

#include <string>
#include <vector>

#include "io/h5_file.hpp"

namespace phasmid::io {

// Samples per chunk and per block read: 32 KiB of doubles.
inline constexpr size_t kStreamBlock = 4096;

// Rows 0, stride, 2 stride, ... of the float dataset `path` (all of each row's other
// dimensions), read by hyperslab: a reader allocates ceil(rows / stride) rows, however long the
// dataset. One line naming the file and dataset if it is not a numeric dataset of rank 1 or 2.
std::vector<double> read_strided(const H5Reader& r, const std::string& path, hsize_t stride);

class AppendedDataset {
 public:
  AppendedDataset(H5Writer& w, const std::string& path, const std::string& units);
  ~AppendedDataset();
  AppendedDataset(const AppendedDataset&) = delete;
  AppendedDataset& operator=(const AppendedDataset&) = delete;
  void append(const double* values, size_t n);
  hsize_t size() const { return size_; }
  hid_t id() const { return ds_; }
  const std::string& path() const { return path_; }

 private:
  H5Writer& w_;
  std::string path_;
  hid_t ds_ = -1;
  hsize_t size_ = 0;
};

class BlockCursor {
 public:
  BlockCursor(hid_t ds, const std::string& what);
  double at(hsize_t i);  // value i (i >= the window's first index)
  hsize_t size() const { return size_; }

 private:
  hid_t ds_;
  std::string what_;
  hsize_t size_ = 0, base_ = 0;
  std::vector<double> window_;
};

}  // namespace phasmid::io
