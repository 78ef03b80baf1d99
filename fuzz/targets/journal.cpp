// Fuzz target: the sweep journal reader of `phasmid sweep --resume` (sweep/sweep_store.hpp).
// The input is the journal after its header line: the target writes the header of a fixed
// sweep (by creating a fresh journal), appends the input and reopens the file with resume, so
// every record reaches decode_record and the torn-tail handling. Each line also goes through
// decode_record directly.
#include <fstream>
#include <sstream>

#include "common/error.hpp"
#include "fuzz_input.hpp"
#include "sweep/sweep_store.hpp"

namespace {
constexpr std::uint64_t kFingerprint = 0x0123456789abcdefull;
constexpr std::size_t kPoints = 16;

const std::string& header() {
  static const std::string h = [] {
    const std::string path = phasmid::fuzz::scratch_path("header.journal");
    { phasmid::sweep::Journal fresh(path, kFingerprint, kPoints, false); }
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }();
  return h;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string body = phasmid::fuzz::as_text(data, size);
  std::istringstream lines(body);
  for (std::string line; std::getline(lines, line);) {
    std::size_t index;
    phasmid::sweep::PointResult r;
    phasmid::sweep::decode_record(line, index, r);
  }
  const std::string path = phasmid::fuzz::scratch_path("resume.journal");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << header() << body;
  }
  try {
    phasmid::sweep::Journal j(path, kFingerprint, kPoints, true);
    for (const auto& [index, r] : j.recovered())
      if (index >= kPoints) __builtin_trap();  // recovered() promises indices of this sweep only
  } catch (const phasmid::Error&) {
  }
  return 0;
}
