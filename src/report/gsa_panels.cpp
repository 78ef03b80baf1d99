#include "report/panels.hpp"

#include <cmath>

#include "gsa/gsa_h5.hpp"
#include "gsa/resolution.hpp"

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

json flags(const std::vector<char>& v) {
  json a = json::array();
  for (char x : v) a.push_back(x != 0);
  return a;
}

// Which indices are resolved at this N, and the size that would resolve the rest (NaN: null).
// n_unresolved counts the indices the report draws (S1 and ST, or mu*); S2 apart.
json resolution(const gsa::GsaResult& g, const gsa::FeatureResult& f) {
  const gsa::FeatureResolution r = gsa::resolve(g, f);
  json j = {{"n_unresolved", r.n_unresolved - r.n_unresolved_s2}, {"n_unresolved_s2", r.n_unresolved_s2},
            {"n_to_resolve", std::isfinite(r.n_to_resolve) ? json(r.n_to_resolve) : json()}};
  if (g.method == "sobol") j["S1"] = flags(r.S1), j["ST"] = flags(r.ST);
  else j["mu_star"] = flags(r.mu_star);
  return j;
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
  json out = {{"method", g.method}, {"confidence", g.bootstrap.confidence}, {"resamples", g.bootstrap.resamples},
              {"resolution", g.resolution}};
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
    j["resolved"] = resolution(g, f);
    features.push_back(j);
  }
  out["features"] = features;
  return out;
}

}  // namespace phasmid::report
