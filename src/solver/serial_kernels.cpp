#include "solver/serial_kernels.hpp"

#include <nvector/nvector_serial.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <utility>

// Semantics follow SUNDIALS 6.4's nvector_serial.c (documented in the N_Vector chapter of the
// user guide). Elementwise loops read element i of every operand before writing element i of
// the result, so results may alias operands (CVODES relies on z == x in several places);
// `ivdep` tells the compiler that this is safe to vectorise.

namespace phasmid::solver {
namespace {

using Real = sunrealtype;
using Index = sunindextype;

inline Real* data(N_Vector v) { return NV_DATA_S(v); }
inline Index length(N_Vector v) { return NV_LENGTH_S(v); }

// Four doubles as one vector (GCC and Clang's vector extension), so that a short kernel can
// keep its running sums in vector registers from one operand vector to the next. Each lane
// multiplies and adds as scalar code would, so the results are the same bit for bit.
typedef Real Vec4 __attribute__((vector_size(4 * sizeof(Real))));
inline Vec4 load4(const Real* x) {
  Vec4 v;
  std::memcpy(&v, x, sizeof v);
  return v;
}
inline void store4(Real* z, const Vec4& v) { std::memcpy(z, &v, sizeof v); }

// Kernels for short vectors (a joint network: 26 states, 20 with rate motoneurons; its parts
// 12 and 14), where a loop's set-up, remainder handling and call overhead cost more than its
// arithmetic: K<F, R>::run handles F * 4 + R elements with the loops' bounds known to the
// compiler. kShort<K>[n] is K's run for length n <= kShortVector.
constexpr int kShortVector = 32;
template <template <int, int> class K, int... N>
constexpr std::array<decltype(&K<0, 0>::run), sizeof...(N)> short_kernels(std::integer_sequence<int, N...>) {
  return {&K<N / 4, N % 4>::run...};
}
template <template <int, int> class K>
constexpr auto kShort = short_kernels<K>(std::make_integer_sequence<int, kShortVector + 1>{});

// z = a x + b y, four elements at a time (z may be x or y).
template <int F, int R>
struct LinearSumShort {
  static void run(Real a, const Real* x, Real b, const Real* y, Real* z) {
    for (int j = 0; j < F; ++j) store4(z + 4 * j, a * load4(x + 4 * j) + b * load4(y + 4 * j));
    for (int j = 4 * F; j < 4 * F + R; ++j) z[j] = a * x[j] + b * y[j];
  }
};

// z = c x (z may be x).
template <int F, int R>
struct ScaleShort {
  static void run(Real c, const Real* x, Real* z) {
    for (int j = 0; j < F; ++j) store4(z + 4 * j, c * load4(x + 4 * j));
    for (int j = 4 * F; j < 4 * F + R; ++j) z[j] = c * x[j];
  }
};

void linear_sum(Real a, N_Vector x, Real b, N_Vector y, N_Vector z) {
  const Real *xd = data(x), *yd = data(y);
  Real* zd = data(z);
  const Index n = length(x);
  if (n <= kShortVector) return kShort<LinearSumShort>[n](a, xd, b, yd, zd);
#pragma GCC ivdep
  for (Index i = 0; i < n; ++i) zd[i] = a * xd[i] + b * yd[i];
}

void constant(Real c, N_Vector z) {
  std::fill(data(z), data(z) + length(z), c);
}

void prod(N_Vector x, N_Vector y, N_Vector z) {
  const Real *xd = data(x), *yd = data(y);
  Real* zd = data(z);
  const Index n = length(x);
#pragma GCC ivdep
  for (Index i = 0; i < n; ++i) zd[i] = xd[i] * yd[i];
}

void div(N_Vector x, N_Vector y, N_Vector z) {
  const Real *xd = data(x), *yd = data(y);
  Real* zd = data(z);
  const Index n = length(x);
#pragma GCC ivdep
  for (Index i = 0; i < n; ++i) zd[i] = xd[i] / yd[i];
}

void scale(Real c, N_Vector x, N_Vector z) {
  const Real* xd = data(x);
  Real* zd = data(z);
  const Index n = length(x);
  if (n <= kShortVector) return kShort<ScaleShort>[n](c, xd, zd);
#pragma GCC ivdep
  for (Index i = 0; i < n; ++i) zd[i] = c * xd[i];
}

void abs_value(N_Vector x, N_Vector z) {
  const Real* xd = data(x);
  Real* zd = data(z);
  const Index n = length(x);
#pragma GCC ivdep
  for (Index i = 0; i < n; ++i) zd[i] = std::abs(xd[i]);
}

void inv(N_Vector x, N_Vector z) {
  const Real* xd = data(x);
  Real* zd = data(z);
  const Index n = length(x);
#pragma GCC ivdep
  for (Index i = 0; i < n; ++i) zd[i] = 1.0 / xd[i];
}

void add_const(N_Vector x, Real b, N_Vector z) {
  const Real* xd = data(x);
  Real* zd = data(z);
  const Index n = length(x);
#pragma GCC ivdep
  for (Index i = 0; i < n; ++i) zd[i] = xd[i] + b;
}

Real dot(N_Vector x, N_Vector y) {
  const Real *xd = data(x), *yd = data(y);
  Real sum = 0.0;
  for (Index i = 0, n = length(x); i < n; ++i) sum += xd[i] * yd[i];
  return sum;
}

Real max_norm(N_Vector x) {
  const Real* xd = data(x);
  Real m = 0.0;
  for (Index i = 0, n = length(x); i < n; ++i) m = std::max(m, std::abs(xd[i]));
  return m;
}

Real wsqr_sum(N_Vector x, N_Vector w) {
  const Real *xd = data(x), *wd = data(w);
  Real sum = 0.0;
  for (Index i = 0, n = length(x); i < n; ++i) {
    const Real v = xd[i] * wd[i];
    sum += v * v;
  }
  return sum;
}

Real wsqr_sum_mask(N_Vector x, N_Vector w, N_Vector id) {
  const Real *xd = data(x), *wd = data(w), *idd = data(id);
  Real sum = 0.0;
  for (Index i = 0, n = length(x); i < n; ++i)
    if (idd[i] > 0.0) {
      const Real v = xd[i] * wd[i];
      sum += v * v;
    }
  return sum;
}

Real wrms_norm(N_Vector x, N_Vector w) { return std::sqrt(wsqr_sum(x, w) / length(x)); }

Real wrms_norm_mask(N_Vector x, N_Vector w, N_Vector id) {
  return std::sqrt(wsqr_sum_mask(x, w, id) / length(x));
}

Real min_value(N_Vector x) {
  const Real* xd = data(x);
  Real m = xd[0];
  for (Index i = 1, n = length(x); i < n; ++i) m = std::min(m, xd[i]);
  return m;
}

Real wl2_norm(N_Vector x, N_Vector w) { return std::sqrt(wsqr_sum(x, w)); }

Real l1_norm(N_Vector x) {
  const Real* xd = data(x);
  Real sum = 0.0;
  for (Index i = 0, n = length(x); i < n; ++i) sum += std::abs(xd[i]);
  return sum;
}

void compare(Real c, N_Vector x, N_Vector z) {
  const Real* xd = data(x);
  Real* zd = data(z);
  const Index n = length(x);
#pragma GCC ivdep
  for (Index i = 0; i < n; ++i) zd[i] = std::abs(xd[i]) >= c ? 1.0 : 0.0;
}

sunbooleantype inv_test(N_Vector x, N_Vector z) {
  const Real* xd = data(x);
  Real* zd = data(z);
  sunbooleantype no_zero = SUNTRUE;
  for (Index i = 0, n = length(x); i < n; ++i) {
    if (xd[i] == 0.0) no_zero = SUNFALSE;
    else zd[i] = 1.0 / xd[i];
  }
  return no_zero;
}

// z = sum_i c_i X_i (z may be X_0).
// One pass over the elements, the sum of each kept in a register: an integrator's stage sums
// have up to ~13 short vectors (one joint's 26 states), where a pass per vector stored and
// reloaded z as often. The terms are added in the same order either way.
constexpr int kOnePassVectors = 16;

// linear_combination for a short vector of F * 4 + R elements: every sum stays in a register
// while the terms are added vector by vector, so a term costs one multiply and one add per four
// elements (the general loop below reloads its pointers and coefficients for every group of
// four: twice the instructions on a joint's 14 states). The same order of terms per element.
template <int F, int R>
struct CombinationShort {
  static void run(int nvec, const Real* c, N_Vector* X, Real* zd) {
    Vec4 s[F > 0 ? F : 1];
    Real r[R > 0 ? R : 1];
    const Real* x0 = data(X[0]);
    for (int j = 0; j < F; ++j) s[j] = c[0] * load4(x0 + 4 * j);
    for (int j = 0; j < R; ++j) r[j] = c[0] * x0[4 * F + j];
    for (int i = 1; i < nvec; ++i) {
      const Real ci = c[i], *xi = data(X[i]);
      for (int j = 0; j < F; ++j) s[j] += ci * load4(xi + 4 * j);
      for (int j = 0; j < R; ++j) r[j] += ci * xi[4 * F + j];
    }
    for (int j = 0; j < F; ++j) store4(zd + 4 * j, s[j]);
    for (int j = 0; j < R; ++j) zd[4 * F + j] = r[j];
  }
};

int linear_combination(int nvec, Real* c, N_Vector* X, N_Vector z) {
  const Index n = length(z);
  if (n <= kShortVector) {
    kShort<CombinationShort>[n](nvec, c, X, data(z));
    return 0;
  }
  Real* zd = data(z);
  const Real* x0 = data(X[0]);
  const Real c0 = c[0];
  if (nvec <= kOnePassVectors) {
    const Real* xs[kOnePassVectors];
    for (int i = 0; i < nvec; ++i) xs[i] = data(X[i]);
    Index k = 0;
    for (; k + 4 <= n; k += 4) {  // four elements at a time in one vector register
      Vec4 s = c0 * load4(x0 + k);
      for (int i = 1; i < nvec; ++i) s += c[i] * load4(xs[i] + k);
      store4(zd + k, s);
    }
    for (; k < n; ++k) {
      Real sum = c0 * x0[k];
      for (int i = 1; i < nvec; ++i) sum += c[i] * xs[i][k];
      zd[k] = sum;
    }
    return 0;
  }
#pragma GCC ivdep
  for (Index k = 0; k < n; ++k) zd[k] = c0 * x0[k];
  for (int i = 1; i < nvec; ++i) {
    const Real* xd = data(X[i]);
    const Real ci = c[i];
#pragma GCC ivdep
    for (Index k = 0; k < n; ++k) zd[k] += ci * xd[k];
  }
  return 0;
}

// Z_i = a_i x + Y_i.
int scale_add_multi(int nvec, Real* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  const Index n = length(x);
  const Real* xd = data(x);
  for (int i = 0; i < nvec; ++i) {
    const Real* yd = data(Y[i]);
    Real* zd = data(Z[i]);
    const Real ai = a[i];
#pragma GCC ivdep
    for (Index k = 0; k < n; ++k) zd[k] = ai * xd[k] + yd[k];
  }
  return 0;
}

int dot_prod_multi(int nvec, N_Vector x, N_Vector* Y, Real* dots) {
  for (int i = 0; i < nvec; ++i) dots[i] = dot(x, Y[i]);
  return 0;
}

int linear_sum_array(int nvec, Real a, N_Vector* X, Real b, N_Vector* Y, N_Vector* Z) {
  for (int i = 0; i < nvec; ++i) linear_sum(a, X[i], b, Y[i], Z[i]);
  return 0;
}

int scale_array(int nvec, Real* c, N_Vector* X, N_Vector* Z) {
  for (int i = 0; i < nvec; ++i) scale(c[i], X[i], Z[i]);
  return 0;
}

int const_array(int nvec, Real c, N_Vector* Z) {
  for (int i = 0; i < nvec; ++i) constant(c, Z[i]);
  return 0;
}

int wrms_norm_array(int nvec, N_Vector* X, N_Vector* W, Real* nrm) {
  for (int i = 0; i < nvec; ++i) nrm[i] = wrms_norm(X[i], W[i]);
  return 0;
}

int wrms_norm_mask_array(int nvec, N_Vector* X, N_Vector* W, N_Vector id, Real* nrm) {
  for (int i = 0; i < nvec; ++i) nrm[i] = wrms_norm_mask(X[i], W[i], id);
  return 0;
}

// Z[j][i] = a_j X[i] + Y[j][i] for i < nvec, j < nsum.
int scale_add_multi_array(int nvec, int nsum, Real* a, N_Vector* X, N_Vector** Y, N_Vector** Z) {
  const Index n = length(X[0]);
  for (int i = 0; i < nvec; ++i) {
    const Real* xd = data(X[i]);
    for (int j = 0; j < nsum; ++j) {
      const Real* yd = data(Y[j][i]);
      Real* zd = data(Z[j][i]);
      const Real aj = a[j];
#pragma GCC ivdep
      for (Index k = 0; k < n; ++k) zd[k] = aj * xd[k] + yd[k];
    }
  }
  return 0;
}

// Z[i] = sum_j c_j X[j][i] for i < nvec, j < nsum (Z[i] may be X[0][i]).
int linear_combination_array(int nvec, int nsum, Real* c, N_Vector** X, N_Vector* Z) {
  const Index n = length(Z[0]);
  for (int i = 0; i < nvec; ++i) {
    Real* zd = data(Z[i]);
    const Real* x0 = data(X[0][i]);
    const Real c0 = c[0];
#pragma GCC ivdep
    for (Index k = 0; k < n; ++k) zd[k] = c0 * x0[k];
    for (int j = 1; j < nsum; ++j) {
      const Real* xd = data(X[j][i]);
      const Real cj = c[j];
#pragma GCC ivdep
      for (Index k = 0; k < n; ++k) zd[k] += cj * xd[k];
    }
  }
  return 0;
}

}  // namespace

void install_serial_kernels(N_Vector v) {
  if (N_VGetVectorID(v) != SUNDIALS_NVEC_SERIAL) return;
  N_Vector_Ops ops = v->ops;
  ops->nvlinearsum = linear_sum;
  ops->nvconst = constant;
  ops->nvprod = prod;
  ops->nvdiv = div;
  ops->nvscale = scale;
  ops->nvabs = abs_value;
  ops->nvinv = inv;
  ops->nvaddconst = add_const;
  ops->nvdotprod = dot;
  ops->nvmaxnorm = max_norm;
  ops->nvwrmsnorm = wrms_norm;
  ops->nvwrmsnormmask = wrms_norm_mask;
  ops->nvmin = min_value;
  ops->nvwl2norm = wl2_norm;
  ops->nvl1norm = l1_norm;
  ops->nvcompare = compare;
  ops->nvinvtest = inv_test;
  ops->nvlinearcombination = linear_combination;
  ops->nvscaleaddmulti = scale_add_multi;
  ops->nvdotprodmulti = dot_prod_multi;
  ops->nvlinearsumvectorarray = linear_sum_array;
  ops->nvscalevectorarray = scale_array;
  ops->nvconstvectorarray = const_array;
  ops->nvwrmsnormvectorarray = wrms_norm_array;
  ops->nvwrmsnormmaskvectorarray = wrms_norm_mask_array;
  ops->nvscaleaddmultivectorarray = scale_add_multi_array;
  ops->nvlinearcombinationvectorarray = linear_combination_array;
  ops->nvdotprodlocal = dot;
  ops->nvmaxnormlocal = max_norm;
  ops->nvminlocal = min_value;
  ops->nvl1normlocal = l1_norm;
  ops->nvinvtestlocal = inv_test;
  ops->nvwsqrsumlocal = wsqr_sum;
  ops->nvwsqrsummasklocal = wsqr_sum_mask;
}

}  // namespace phasmid::solver
