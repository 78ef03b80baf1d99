#pragma once
// The one value of a dataset written as a scalar. A file is outside phasmid's control: a
// dataset that should hold one value and holds none is a damaged file, reported in one line
// naming file and dataset, never an out-of-range read.
#include <string>

#include "common/error.hpp"
#include "io/h5_file.hpp"

namespace phasmid::io {

inline double read_scalar(const H5Reader& r, const std::string& path) {
  const auto v = r.read_doubles(path);
  if (v.empty()) throw Error(r.path() + ": dataset " + path + " holds no value");
  return v.front();
}

inline std::string read_scalar_string(const H5Reader& r, const std::string& path) {
  const auto v = r.read_strings(path);
  if (v.empty()) throw Error(r.path() + ": dataset " + path + " holds no string");
  return v.front();
}

}  // namespace phasmid::io
