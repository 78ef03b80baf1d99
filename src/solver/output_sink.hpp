#pragma once
// Where a run's output samples go when they are not kept in memory (SolverOptions::output_sink):
// the drivers hand every output row to record() in time order, once, as soon as every state of
// it is known (a partitioned run waits for its slowest part). `simulate` streams them to HDF5
// (io/trajectory_stream.hpp) so that its memory does not grow with t_end_ms.
#include <cstddef>

namespace phasmid::solver {

class OutputSink {
 public:
  virtual ~OutputSink() = default;
  // The state y[0..n) at output time t (ms); y is valid during the call only.
  virtual void record(double t, const double* y, size_t n) = 0;
};

}  // namespace phasmid::solver
