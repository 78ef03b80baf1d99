#include "fuzz_input.hpp"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace phasmid::fuzz {
namespace {
std::filesystem::path& scratch_dir() {
  static std::filesystem::path dir;
  return dir;
}
void remove_scratch_dir() {
  std::error_code ec;
  std::filesystem::remove_all(scratch_dir(), ec);
}
}  // namespace

std::string scratch_path(const std::string& name) {
  static const std::filesystem::path dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::filesystem::path d = std::filesystem::path(tmp && *tmp ? tmp : "/tmp") /
                              ("phasmid-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    scratch_dir() = d;
    std::atexit(remove_scratch_dir);  // a run that ends normally leaves nothing behind
    return d;
  }();
  return (dir / name).string();
}

std::string write_scratch(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = scratch_path(name);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace phasmid::fuzz
