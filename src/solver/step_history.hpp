#pragma once
// One part's recent steps in a windowed partitioned run (solver/partitioned_simulator.hpp), by
// which its states at the other parts' events, at outputs and at roll-backs are found after a
// window, when the part may be several steps past those times.
//
// Each step keeps the part's states and their time derivatives at both ends, and a state
// inside it is the cubic Hermite interpolant of the two: Dormand-Prince's own (dopri5's
// interpolant is degree 3) itself, and for CVODES a C1 dense output of the same order as that
// of an order-3 method (the step's own Nordsieck polynomial would cost q + 1 evaluations of
// the whole state per step, where this needs one: the derivative at the step's end; the
// start is the previous step's end). Why: the record is taken at every step of every part
// and read at a few thousand times in a run (outputs, events).
//
// Contract: record() appends a step [t0, tn]; a step that continues the previous one
// (t0 equal to its tn, no restart between) takes its start values from it, any other passes
// them. at() finds the latest step covering t. drop_before() keeps at least the last step.
#include <cstddef>
#include <deque>
#include <vector>

namespace phasmid::solver {

class StepHistory {
 public:
  explicit StepHistory(size_t n = 0) : n_(n) {}

  // The step over [t0, tn] with the end values yn, fn; y0 and f0 (the start values) are
  // taken from the previous step when null, and t0 is then its tn.
  void record(double t0, double tn, const double* y0, const double* f0, const double* yn, const double* fn);
  // Whether the last recorded step ends at t (a following step may carry its end values).
  bool continues_at(double t) const { return !steps_.empty() && steps_.back().tn == t; }
  // The states at t (own indices 0..n-1) into row[index[i]]; false if no step covers t.
  bool at(double t, const std::vector<size_t>& index, double* row) const;
  // Forget the steps that end before t (never the last one), and those that start at or
  // after t (a roll-back to t).
  void drop_before(double t);
  void drop_from(double t);

 private:
  struct Step {
    double t0 = 0.0, tn = 0.0;
    std::vector<double> v;  // y0, f0, yn, fn: n values each
  };
  size_t n_;
  std::deque<Step> steps_;
  std::vector<std::vector<double>> spare_;  // buffers of dropped steps, for reuse
};

}  // namespace phasmid::solver
