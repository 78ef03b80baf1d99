#pragma once
// Compiled replacements for the arithmetic of SUNDIALS' serial N_Vector.
//
// Why: for phasmid's 20-240-state models CVODES spends much of a step in these kernels, and
// SUNDIALS' generic loops (even built with optimisation, scripts/build_sundials.sh; Debian's
// binary package is built without) do not know the short lengths. Together with
// solver/matrix_kernels.hpp they make forward-sensitivity runs markedly cheaper; plain runs
// are the same either way (docs/performance.md "What the build contributes"). The
// replacements keep the serial vector's content (length, data) and its
// semantics, so every other SUNDIALS routine (clone, destroy, array pointer) still applies;
// clones copy the ops table and so inherit the kernels.
#include <sundials/sundials_nvector.h>

namespace phasmid::solver {

// Installs the kernels into `v`'s ops table (v must be a serial vector; otherwise a no-op).
// Vectors cloned from `v` afterwards use them too.
void install_serial_kernels(N_Vector v);

}  // namespace phasmid::solver
