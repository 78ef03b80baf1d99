#pragma once
// Numbers in one-line messages: printf's %g (shortest of fixed and exponent form).
#include <cstdio>
#include <string>

namespace phasmid {

inline std::string format_g(double v, int digits = 6) {
  char b[40];
  std::snprintf(b, sizeof b, "%.*g", digits, v);
  return b;
}

}  // namespace phasmid
