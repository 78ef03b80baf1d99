#pragma once
// exp of n arguments at once: e[i] = exp(x[i]). The network's right-hand side takes about 45
// exponentials per evaluation (model/neurons.hpp, two phases), and one libm call each
// dominated the right-hand side's time (docs/performance.md).
// For double the loop is vectorised over glibc's vector math library (libmvec, the variant the
// compiler picks for the instruction set: 4 lanes with AVX2, 2 with SSE2), whose results agree
// with the scalar exp to a few ulp; for any other type (ceres::Jet) each argument is taken
// alone. Where the compiler cannot vectorise the loop (other compilers, other architectures)
// it is the scalar loop: the same values up to rounding.
#include <cmath>
#include <cstddef>

namespace phasmid::model {

void exp_each(const double* x, double* e, size_t n);

template <class T>
void exp_each(const T* x, T* e, size_t n) {
  using std::exp;
  for (size_t i = 0; i < n; ++i) e[i] = exp(x[i]);
}

}  // namespace phasmid::model
