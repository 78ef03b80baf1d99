#pragma once
// Files embedded into the binary at build time (cmake/Embed.cmake): configs/*.toml and
// reports/* assets, keyed by their path relative to the source root ("configs/x.toml").
#include <map>
#include <string>

namespace phasmid::embedded {
const std::map<std::string, std::string>& files();
}
