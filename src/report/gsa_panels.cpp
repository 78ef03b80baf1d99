#include "report/gsa_panels.hpp"

#include <cmath>

#include "gsa/gsa_h5.hpp"

namespace phasmid::report {
namespace {
using nlohmann::json;

json nums(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(std::isfinite(x) ? json(x) : json());
  return a;
}

template <class Indices>
json rows(const std::vector<Indices>& levels, std::vector<double> Indices::*field) {
  json a = json::array();
  for (const Indices& x : levels) a.push_back(nums(x.*field));
  return a;
}

json counts(const gsa::OutputCounts& c) {
  return {{"n_nonfinite", c.n_nonfinite}, {"n_dropped", c.n_dropped}, {"n_used", c.n_used}};
}

json sobol_feature(const gsa::FeatureResult& f) {
  const gsa::SobolIndices& s = f.sobol;
  json j = {{"S1", nums(s.S1)}, {"S1_conf", nums(s.S1_conf)}, {"ST", nums(s.ST)}, {"ST_conf", nums(s.ST_conf)},
            {"counts", counts(s.counts)}};
  j["convergence"] = {{"n", f.convergence_n},
                      {"S1", rows(f.sobol_convergence, &gsa::SobolIndices::S1)},
                      {"S1_conf", rows(f.sobol_convergence, &gsa::SobolIndices::S1_conf)},
                      {"ST", rows(f.sobol_convergence, &gsa::SobolIndices::ST)},
                      {"ST_conf", rows(f.sobol_convergence, &gsa::SobolIndices::ST_conf)}};
  return j;
}

json morris_feature(const gsa::FeatureResult& f) {
  const gsa::MorrisIndices& m = f.morris;
  json j = {{"mu", nums(m.mu)}, {"mu_star", nums(m.mu_star)}, {"mu_star_conf", nums(m.mu_star_conf)},
            {"sigma", nums(m.sigma)}, {"counts", counts(m.counts)}};
  j["convergence"] = {{"n", f.convergence_n},
                      {"mu_star", rows(f.morris_convergence, &gsa::MorrisIndices::mu_star)},
                      {"mu_star_conf", rows(f.morris_convergence, &gsa::MorrisIndices::mu_star_conf)}};
  return j;
}

}  // namespace

json extract_gsa(const io::H5Reader& r) {
  const gsa::GsaResult g = gsa::read_gsa_h5(r);
  json out = {{"method", g.method}, {"confidence", g.bootstrap.confidence}, {"resamples", g.bootstrap.resamples}};
  json names = json::array(), units = json::array();
  for (const auto& p : g.parameters) names.push_back(p.name), units.push_back(p.unit);
  out["parameter_names"] = names;
  out["parameter_units"] = units;
  if (g.method == "sobol") out["N"] = g.saltelli.n_base, out["rows"] = g.saltelli.rows();
  else out["r"] = g.morris.trajectories, out["levels"] = g.morris.levels, out["rows"] = g.morris.rows();
  json features = json::array();
  for (const gsa::FeatureResult& f : g.features) {
    json j = g.method == "sobol" ? sobol_feature(f) : morris_feature(f);
    j["name"] = f.name;
    j["units"] = f.unit;
    features.push_back(j);
  }
  out["features"] = features;
  return out;
}

}  // namespace phasmid::report
