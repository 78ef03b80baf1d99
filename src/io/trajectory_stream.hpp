#pragma once
// Writes a run's trajectory in the layout of docs/hdf5.md ("/trajectory", "/body") sample by
// sample, as the solver reaches them (solver::OutputSink), so that what it holds does not grow
// with the length of the run: every dataset is extended by blocks of io::kStreamBlock samples.
// finish() writes the last block, then what needs later samples or the whole past — the
// right-hand legs of the six-leg pattern (the left delayed by lag * period) and the body path
// of curve walking — by reading the written datasets back in blocks. Every value is computed
// as write_trajectory computes it from a trajectory in memory (it uses this class).
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/h5_stream.hpp"
#include "model/ode_model.hpp"
#include "solver/output_sink.hpp"

namespace phasmid::io {

class TrajectoryStream : public solver::OutputSink {
 public:
  TrajectoryStream(H5Writer& w, const model::OdeModel& m);
  void record(double t, const double* y, size_t n) override;
  void finish();

 private:
  enum class Kind { Degrees, Raw, SwingAboveRad, SwingAboveDeg };
  struct Column {
    size_t state;
    Kind kind;
    double threshold;
    std::unique_ptr<AppendedDataset> ds;
  };
  void add(const std::string& path, const std::string& units, size_t state, Kind kind, double threshold = 0.0);
  void flush();
  void write_right_side();
  void write_body_path();
  AppendedDataset& dataset(const std::string& path);

  H5Writer& w_;
  const model::OdeModel& m_;
  AppendedDataset time_;
  std::vector<Column> columns_;
  std::map<std::string, size_t> by_path_;
  std::vector<double> t_block_, block_;  // block_: column-major, kStreamBlock per column
  size_t fill_ = 0;
  bool finished_ = false;
};

}  // namespace phasmid::io
