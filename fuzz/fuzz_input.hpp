#pragma once
// Helpers shared by the fuzz targets (fuzz/targets/*.cpp, docs/reliability.md): the input as
// text, and as a file for the readers that only take a path (HDF5, the sweep journal).
//
// Contract of every target: the reader either returns or throws phasmid::Error; anything else
// (another exception, a signal, a sanitizer report, a leak, a timeout) is a defect.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.hpp"

namespace phasmid::fuzz {

inline std::string as_text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// A private directory for this process (created once, under $TMPDIR or /tmp, removed at
// exit), and a path in it.
std::string scratch_path(const std::string& name);
// Writes `bytes` to scratch_path(name) and returns that path.
std::string write_scratch(const std::string& name, const std::uint8_t* data, std::size_t size);

// Runs f; a phasmid::Error is the reader refusing the input, which is fine. Other exceptions
// pass through and fail the target.
template <class F>
void attempt(F&& f) {
  try {
    f();
  } catch (const phasmid::Error&) {
  }
}

}  // namespace phasmid::fuzz
