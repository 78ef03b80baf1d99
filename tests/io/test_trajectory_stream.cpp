// Streamed output (io/trajectory_stream.hpp, SolverOptions::output_sink): `simulate` hands the
// samples to the file as the solver reaches them instead of keeping the trajectory. The file
// must hold the same datasets, bit for bit, as the one written from the trajectory in memory:
// on the whole-system driver, on the partitioned driver (whose parts finish an output at
// different times and roll back at triggered commands), with the six-leg pattern of the
// three-leg model (the right side read back delayed) and the body path of curve walking (read
// back in blocks). Runs longer than one block of io::kStreamBlock samples, so that blocks join.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "build_info.hpp"
#include "config/config.hpp"
#include "io/h5_file.hpp"
#include "io/trajectory_stream.hpp"

#include "../solver/middle_leg_trigger_config.hpp"

using namespace phasmid;

namespace {

constexpr size_t kStreamBlockSamples = io::kStreamBlock + 1;  // more than one block

struct Written {
  std::string path;
  std::vector<std::string> notes;
};

// simulate's file for the config (in configs/, or a path), with the samples kept in memory or streamed.
Written simulate(const std::string& name, double t_end_ms, double output_dt_ms, solver::Partitioning partitioning,
                 bool streamed) {
  const std::string path = name.find('/') == std::string::npos ? std::string(PHASMID_SOURCE_DIR) + "/configs/" + name : name;
  const config::Config cfg = config::load_config(path);
  auto scenario = config::build_scenario(cfg);
  config::SimulationSettings s = config::simulation_settings(cfg, scenario.get());
  s.t_end_ms = t_end_ms;
  if (output_dt_ms > 0) s.output_dt_ms = output_dt_ms;
  s.solver.partitioning = partitioning;
  // The network parts' own tolerances exist only with the spiking cells apart (SolverOptions::validate).
  if (partitioning != solver::Partitioning::Neurons) s.solver.stiff_part_atol_by_unit.clear();
  Written out{::testing::TempDir() + "stream_" + name.substr(name.rfind('/') + 1) + (streamed ? ".streamed.h5" : ".memory.h5"), {}};
  io::H5Writer w(out.path);
  std::optional<io::TrajectoryStream> stream;
  if (streamed) s.solver.output_sink = &stream.emplace(w, *scenario->ode_model());
  auto run = scenario->run(scenario->parameters().values(), s);
  EXPECT_EQ(run->solution() == nullptr, streamed);
  if (stream) stream->finish();
  run->write(w);
  w.commit();
  out.notes = run->notes();
  return out;
}

void collect_datasets(const io::H5Reader& f, const std::string& group, std::vector<std::string>& out) {
  for (const std::string& c : f.children(group)) {
    const std::string path = (group == "/" ? "" : group) + "/" + c;
    if (f.is_group(path)) collect_datasets(f, path, out);
    else if (path.rfind("/parameters/", 0) != 0 || path == "/parameters/values") out.push_back(path);
  }
}

// Every numeric dataset of a in b with the same shape, values (bytes) and units; none extra in b.
void expect_same_datasets(const std::string& a_path, const std::string& b_path, size_t min_samples) {
  io::H5Reader a(a_path), b(b_path);
  std::vector<std::string> in_a, in_b;
  collect_datasets(a, "/", in_a);
  collect_datasets(b, "/", in_b);
  EXPECT_EQ(in_a, in_b);
  EXPECT_GE(a.dims("/trajectory/time").at(0), min_samples);
  for (const std::string& d : in_a) {
    if (!b.exists(d)) continue;
    EXPECT_EQ(a.dims(d), b.dims(d)) << d;
    const std::vector<double> x = a.read_doubles(d), y = b.read_doubles(d);
    ASSERT_EQ(x.size(), y.size()) << d;
    EXPECT_TRUE(x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0) << d << " differs";
    EXPECT_EQ(a.read_string_attribute(d, "units"), b.read_string_attribute(d, "units")) << d;
  }
}

// output_dt_ms 0: the config's.
void expect_streamed_equals_memory(const std::string& name, double t_end_ms, solver::Partitioning partitioning,
                                   double integrators, double output_dt_ms = 0.0) {
  const Written memory = simulate(name, t_end_ms, output_dt_ms, partitioning, false);
  const Written streamed = simulate(name, t_end_ms, output_dt_ms, partitioning, true);
  expect_same_datasets(memory.path, streamed.path, kStreamBlockSamples);
  EXPECT_EQ(memory.notes, streamed.notes);
  EXPECT_EQ(io::H5Reader(streamed.path).read_double_attribute("/trajectory", "integrators"), integrators);
  for (const Written* w : {&memory, &streamed}) {  // one thread: the solve's CPU time is at most its wall time
    io::H5Reader f(w->path);
    const double cpu = f.read_double_attribute("/trajectory", "cpu_seconds");
    const double wall = f.read_double_attribute("/trajectory", "wall_seconds");
    EXPECT_GT(cpu, 0.0) << w->path;
    EXPECT_LE(cpu, 1.1 * wall + 0.01) << w->path;
  }
  std::remove(memory.path.c_str());
  std::remove(streamed.path.c_str());
}

TEST(TrajectoryStream, SingleJointWholeSystem) {
  expect_streamed_equals_memory("single_joint_fti.toml", 9000, solver::Partitioning::Off, 1);
}

TEST(TrajectoryStream, ThreeLegsSixLegPatternPartitioned) {
  expect_streamed_equals_memory("three_legs_tripod.toml", 4500, solver::Partitioning::On, 9);
}

TEST(TrajectoryStream, TriggeredCommandsPartitioned) {
  expect_streamed_equals_memory("gait_tripod_to_tetrapod.toml", 4500, solver::Partitioning::On, 9);
}

// A command at the very touch-down that triggers it: the joint integrators already past it go
// back and write their outputs after it again (on a grid of 0.01 ms, finer than the parts'
// steps, outputs lie between the touch-down and the parts' times when the crossing is taken);
// only the rewritten values may reach the file.
TEST(TrajectoryStream, TriggerAtItsEventRollsPartsBack) {
  const std::string path = ::testing::TempDir() + "stream_middle_leg_trigger.toml";
  FILE* f = std::fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs(test::middle_leg_trigger_config(1000.0, 0.0).c_str(), f);
  std::fclose(f);
  expect_streamed_equals_memory(path, 1500, solver::Partitioning::On, 3, 0.01);
  std::remove(path.c_str());
}

TEST(TrajectoryStream, CurveWalkingBodyPath) {
  expect_streamed_equals_memory("curve_walking.toml", 4500, solver::Partitioning::Off, 1);
}

}  // namespace
