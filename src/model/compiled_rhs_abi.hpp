#pragma once
// What a compiled right-hand side (model/compiled_rhs.hpp) and phasmid share: the generated
// source includes this header, so both sides agree on the layout. Plain C types only.
#include <cstddef>

// The functions the generated code calls back into phasmid, so that their results are those of
// the generic evaluation: the batched exponentials (model/exp_batch.hpp) and a joint's
// acceleration (model/joint.hpp) of the model `model`.
struct PhasmidRhsContext {
  void (*exp_each)(const double* x, double* e, size_t n);
  double (*joint_acceleration)(const void* model, size_t joint, const double* p, double angle, double omega,
                               double k_inc, double k_dec);
  const void* model;
};

// ydot at the generated components' states from the full state y and parameters p (as
// OdeModelPart::rhs for double).
typedef void (*PhasmidRhsFn)(double t, const double* y, const double* p, double* ydot, const PhasmidRhsContext* ctx);
