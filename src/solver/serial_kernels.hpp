#pragma once
// Compiled replacements for the arithmetic of SUNDIALS' serial N_Vector.
//
// Why: Debian's libsundials (6.4.1+dfsg1-3, the package phasmid builds against) is compiled
// without optimisation (its N_VWSqrSumLocal_Serial keeps the loop index and the running sum on
// the stack; bench/results shows the disassembly check). CVODES spends most of a step in
// these kernels for phasmid's 20-240-state models, so unoptimised loops there cost more than
// the model itself (measured in bench/results). The replacements keep the serial vector's content (length, data) and its
// semantics, so every other SUNDIALS routine (clone, destroy, array pointer) still applies;
// clones copy the ops table and so inherit the kernels.
#include <sundials/sundials_nvector.h>

namespace phasmid::solver {

// Installs the kernels into `v`'s ops table (v must be a serial vector; otherwise a no-op).
// Vectors cloned from `v` afterwards use them too.
void install_serial_kernels(N_Vector v);

}  // namespace phasmid::solver
