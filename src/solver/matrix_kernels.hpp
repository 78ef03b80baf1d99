#pragma once
// Compiled replacements for the matrix arithmetic CVODES' direct linear solvers call every
// Newton setup (M = I - gamma J: zero, copy, scale-add-identity) and for the dense LU
// factorisation and solve. Same reason as solver/serial_kernels.hpp: with forward
// sensitivities CVODES solves one system per parameter each corrector iteration, and
// SUNDlsMat_denseGETRF/GETRS and SUNMat*_Dense/_Sparse are generic loops (docs/performance.md
// "What the build contributes"). The matrices and the
// solver keep SUNDIALS' content layout (and the dense solver its pivot array), so everything
// else (CVODES' bookkeeping, KLU) works on them unchanged.
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

namespace phasmid::solver {

// A must be a SUNMATRIX_DENSE; ls, if given, the SUNLinSol_Dense built on it.
void install_dense_kernels(SUNMatrix A, SUNLinearSolver ls);
// A must be a SUNMATRIX_SPARSE (CSC or CSR).
void install_sparse_kernels(SUNMatrix A);

}  // namespace phasmid::solver
