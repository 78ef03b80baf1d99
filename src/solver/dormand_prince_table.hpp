#pragma once
// Dormand and Prince's 5(4) pair (J. Comput. Appl. Math. 6, 1980), as ARKODE's
// ARKODE_DORMAND_PRINCE_7_4_5: nodes c, stage matrix A (row 6 is the fifth-order solution's
// weights, so stage 6's input is y_{n+1} and its slope the next step's first: FSAL) and the
// fourth-order embedding's weights (solver/dopri_session.cpp).
namespace phasmid::solver::dormand_prince {

inline constexpr double kC[7] = {0, 0.2, 0.3, 0.8, 8.0 / 9, 1, 1};
inline constexpr double kA[7][6] = {{0},
                                    {0.2},
                                    {3.0 / 40, 9.0 / 40},
                                    {44.0 / 45, -56.0 / 15, 32.0 / 9},
                                    {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
                                    {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
                                    {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}};
inline constexpr double kBhat[7] = {5179.0 / 57600,     0, 7571.0 / 16695, 393.0 / 640, -92097.0 / 339200,
                                    187.0 / 2100, 1.0 / 40};

}  // namespace phasmid::solver::dormand_prince
