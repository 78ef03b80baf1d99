#pragma once
// The suggestion of an error about a misspelt name ("did you mean ...?"): config keys and
// sections, model kinds, parameters.
#include <string>
#include <vector>

namespace phasmid {

// The element of `candidates` closest to `word` by edit distance ("" if none is close).
std::string nearest(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace phasmid
