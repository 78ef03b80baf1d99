#pragma once
// What a compiled right-hand side (model/compiled_rhs.hpp) and phasmid share: the generated
// source includes this header, so both sides agree on the layout. Plain C types only.
#include <cstddef>

// What the generated code calls back into phasmid, so that its results are those of the generic
// evaluation: the batched exponentials (model/exp_batch.hpp), which pick a vector kernel at run
// time.
struct PhasmidRhsContext {
  void (*exp_each)(const double* x, double* e, size_t n);
};

// ydot at the generated components' own states, from those states y and the states u it reads
// from other parts, packed as the function's layout says (model::RhsLayout), and the
// parameters p: OdeModelPart::rhs for double on packed vectors.
typedef void (*PhasmidRhsFn)(double t, const double* y, const double* u, const double* p, double* ydot,
                             const PhasmidRhsContext* ctx);
