#include "gsa/gsa_run.hpp"

#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "common/error.hpp"

namespace phasmid::gsa {
namespace {

// Subset sizes of the convergence panel: n, n/2, n/4, ... >= kMinConvergenceRows, ascending.
std::vector<std::size_t> subset_sizes(std::size_t n) {
  std::vector<std::size_t> sizes;
  for (std::size_t k = n; k >= kMinConvergenceRows; k /= 2) sizes.insert(sizes.begin(), k);
  return sizes;
}

// The sweep file's points must be this design's rows (same parameters, same order).
void check_points(const io::H5Reader& r, const GsaResult& design) {
  const std::vector<double> pts = r.read_doubles("/sweep/points");
  const std::vector<double> values = scale_to_parameters(design.unit_design(), design.parameters);
  if (pts.size() != values.size())
    throw Error(r.path() + ": /sweep/points has " + std::to_string(pts.size()) + " values, the [gsa] design " +
                std::to_string(values.size()) + " (not this analysis' sweep)");
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (pts[i] != values[i])
      throw Error(r.path() + ": /sweep/points differs from the [gsa] design at row " +
                  std::to_string(i / design.parameters.size()) + " (not this analysis' sweep)");
}

}  // namespace

GsaResult make_design(const GsaSpec& spec, const std::vector<Parameter>& parameters) {
  if (parameters.empty()) throw Error("gsa: no parameters to vary");
  GsaResult r;
  r.method = spec.method;
  r.parameters = parameters;
  r.bootstrap = spec.bootstrap;
  r.resolution = spec.resolution;
  if (spec.method == "sobol") {
    r.saltelli_options = spec.saltelli;
    r.saltelli = saltelli_sample(parameters.size(), spec.saltelli);
  } else if (spec.method == "morris") {
    r.morris_options = spec.morris;
    r.morris = morris_sample(parameters.size(), spec.morris);
  } else {
    throw Error("gsa: method must be \"sobol\" or \"morris\", got \"" + spec.method + "\"");
  }
  return r;
}

void analyse_feature(const GsaResult& d, FeatureResult& f) {
  const std::size_t dim = d.parameters.size();
  f.convergence_n.clear(), f.sobol_convergence.clear(), f.morris_convergence.clear();
  if (d.method == "sobol") {
    const std::size_t block = d.saltelli.block();
    f.sobol = sobol_analyze(dim, d.saltelli.second_order, f.y, d.bootstrap);
    for (std::size_t n : subset_sizes(d.saltelli.n_base)) {
      f.convergence_n.push_back(n);
      if (n == d.saltelli.n_base) f.sobol_convergence.push_back(f.sobol);
      else f.sobol_convergence.push_back(sobol_analyze(dim, d.saltelli.second_order,
                                                       {f.y.begin(), f.y.begin() + n * block}, d.bootstrap));
    }
    return;
  }
  f.morris = morris_analyze(d.morris, f.y, d.bootstrap);
  for (std::size_t n : subset_sizes(d.morris.trajectories)) {
    f.convergence_n.push_back(n);
    if (n == d.morris.trajectories) {
      f.morris_convergence.push_back(f.morris);
      continue;
    }
    MorrisDesign sub = d.morris;
    sub.trajectories = n;
    sub.unit.resize(sub.rows() * dim);
    f.morris_convergence.push_back(morris_analyze(sub, {f.y.begin(), f.y.begin() + sub.rows()}, d.bootstrap));
  }
}

void analyse_sweep_file(const io::H5Reader& r, const GsaSpec& spec, GsaResult& result) {
  check_points(r, result);
  const std::size_t rows = result.unit_design().size() / result.parameters.size();
  for (const std::string& name : spec.features) {
    FeatureResult f;
    f.name = name;
    const std::string path = "/sweep/features/" + name;
    if (r.exists(path)) {
      f.y = r.read_doubles(path);
      f.unit = r.read_string_attribute(path, "units");
    } else {
      f.y.assign(rows, std::numeric_limits<double>::quiet_NaN());
      f.unit = "";
    }
    if (f.y.size() != rows)
      throw Error(r.path() + ": " + path + " has " + std::to_string(f.y.size()) + " values for " + std::to_string(rows) + " points");
    analyse_feature(result, f);
    result.features.push_back(std::move(f));
  }
}

void write_gsa_file(const std::string& sweep_path, const std::string& out, const GsaResult& result,
                    const io::RunInfo& info) {
  io::H5Reader in(sweep_path);  // kept open until the new file has its copies
  io::H5Writer w(out);
  w.write_run_info(info);
  for (const char* group : {"/sweep", "/parameters"})
    if (in.exists(group) && H5Ocopy(in.id(), group, w.id(), group, H5P_DEFAULT, H5P_DEFAULT) < 0)
      throw Error(sweep_path + ": cannot copy " + group + " into " + out);
  write_gsa_h5(w, result);
  w.commit();
}

}  // namespace phasmid::gsa
