#pragma once
// Reading a user's text input (config, kinematic CSV, parameter TSV) in one bounded step: the
// path must be a regular file (not /dev/zero, a fifo or a directory, which never end or never
// begin) no larger than kMaxTextInputBytes, so a wrong path is an error and not an allocation
// that grows until the machine runs out of memory.
#include <cstdint>
#include <string>

namespace phasmid::io {

// 64 MiB: a hundred times the largest recording or config phasmid ships (a documented choice).
inline constexpr std::uintmax_t kMaxTextInputBytes = 64ull << 20;

// The file's text; an Error "<path>: cannot read <what>: <reason>" otherwise.
std::string read_text_file(const std::string& path, const std::string& what);

}  // namespace phasmid::io
