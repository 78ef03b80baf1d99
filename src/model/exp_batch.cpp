#include "model/exp_batch.hpp"

#include <cmath>

// glibc declares exp's vector variants (libmvec) only under -ffast-math; this is the same
// declaration without fast-math's other licences. With -fno-math-errno (this file only,
// CMakeLists.txt) GCC vectorises the loop below with calls to them.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(PHASMID_LIBMVEC)
extern "C" double exp(double) noexcept __attribute__((__simd__("notinbranch")));
#endif

namespace phasmid::model {

void exp_each(const double* __restrict x, double* __restrict e, size_t n) {
#pragma omp simd
  for (size_t i = 0; i < n; ++i) e[i] = exp(x[i]);
}

}  // namespace phasmid::model
