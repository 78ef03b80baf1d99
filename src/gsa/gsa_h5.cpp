#include "gsa/gsa_h5.hpp"

#include <cstdint>
#include <string>
#include <utility>

#include "common/error.hpp"
#include "gsa/resolution.hpp"

namespace phasmid::gsa {
namespace {

const char* const kNonFinitePolicy =
    "a base row's block (Sobol') or a trajectory (Morris) is dropped when any of its outputs is NaN or infinite";
const char* const kCiMethod =
    "bootstrap over base rows (Sobol') or trajectories (Morris); index +- z * sd of the replicates (normal approximation)";

const char* const kResolutionRule =
    "resolved: half-width <= resolution and the index within [-resolution/2, 1 + resolution/2] (Sobol'), "
    "half-width <= resolution * max mu* (Morris); n_to_resolve from the nested subsets' convergence";

hsize_t h(std::size_t n) { return static_cast<hsize_t>(n); }

std::string joined_units(const std::vector<Parameter>& ps) {
  std::string s;
  for (const auto& p : ps) s += (s.empty() ? "" : ", ") + p.unit;
  return s;
}

void write_design(io::H5Writer& w, const GsaResult& r) {
  std::vector<std::string> names, units, scales;
  std::vector<double> lower, upper;
  for (const auto& p : r.parameters) {
    names.push_back(p.name), units.push_back(p.unit), scales.push_back(p.log_scale ? "log" : "lin");
    lower.push_back(p.lower), upper.push_back(p.upper);
  }
  const std::string ulist = joined_units(r.parameters);
  const std::vector<double>& unit = r.unit_design();
  const hsize_t dim = h(r.parameters.size()), rows = h(unit.size() / r.parameters.size());
  w.write("/gsa/design/parameter_names", names);
  w.write("/gsa/design/parameter_units", units);
  w.write("/gsa/design/scale", scales);
  w.write("/gsa/design/lower", lower, ulist);
  w.write("/gsa/design/upper", upper, ulist);
  w.write("/gsa/design/unit", unit, "1", {rows, dim});
  w.write("/gsa/design/values", scale_to_parameters(unit, r.parameters), ulist, {rows, dim});
}

void write_method_attributes(io::H5Writer& w, const GsaResult& r) {
  w.set_attribute("/gsa", "method", r.method);
  w.set_attribute("/gsa", "D", static_cast<double>(r.parameters.size()));
  if (r.method == "sobol") {
    const SaltelliOptions& o = r.saltelli_options;
    w.set_attribute("/gsa", "estimator_S1", "Saltelli et al. 2010");
    w.set_attribute("/gsa", "estimator_ST", "Jansen 1999");
    if (o.second_order) w.set_attribute("/gsa", "estimator_S2", "Saltelli 2002");
    w.set_attribute("/gsa", "N", static_cast<double>(o.n_base));
    w.set_attribute("/gsa", "second_order", o.second_order ? 1.0 : 0.0);
    w.set_attribute("/gsa", "sequence", o.scramble ? "Sobol' (Joe-Kuo), linear matrix scramble + digital shift"
                                                   : "Sobol' (Joe-Kuo), unscrambled");
    w.set_attribute("/gsa", "skip", static_cast<double>(o.skip));
    w.set_attribute("/gsa", "seed", std::to_string(o.seed));
  } else {
    const MorrisOptions& o = r.morris_options;
    w.set_attribute("/gsa", "estimator_mu", "Morris 1991 elementary effects: mu, sigma");
    w.set_attribute("/gsa", "estimator_mu_star", "Campolongo et al. 2007: mean |EE|");
    w.set_attribute("/gsa", "r", static_cast<double>(o.trajectories));
    w.set_attribute("/gsa", "levels", static_cast<double>(o.levels));
    w.set_attribute("/gsa", "delta", r.morris.delta);
    w.set_attribute("/gsa", "pool", static_cast<double>(o.pool));
    w.set_attribute("/gsa", "seed", std::to_string(o.seed));
  }
  w.set_attribute("/gsa", "confidence_level", r.bootstrap.confidence);
  w.set_attribute("/gsa", "bootstrap_resamples", static_cast<double>(r.bootstrap.resamples));
  w.set_attribute("/gsa", "bootstrap_seed", std::to_string(r.bootstrap.seed));
  w.set_attribute("/gsa", "confidence_interval", kCiMethod);
  w.set_attribute("/gsa", "nonfinite_outputs", kNonFinitePolicy);
  w.set_attribute("/gsa", "resolution", r.resolution);
  w.set_attribute("/gsa", "resolution_rule", kResolutionRule);
}

void write_counts(io::H5Writer& w, const std::string& g, const OutputCounts& c) {
  w.set_attribute(g, "n_nonfinite", static_cast<double>(c.n_nonfinite));
  w.set_attribute(g, "n_dropped", static_cast<double>(c.n_dropped));
  w.set_attribute(g, "n_used", static_cast<double>(c.n_used));
}

// Rows of per-parameter vectors (one row per subset size) as one levels x D dataset.
template <class Indices>
void write_rows(io::H5Writer& w, const std::string& path, const std::vector<Indices>& levels,
                std::vector<double> Indices::*field, const std::string& unit, std::size_t dim) {
  std::vector<double> m;
  for (const Indices& x : levels) m.insert(m.end(), (x.*field).begin(), (x.*field).end());
  w.write(path, m, unit, {h(levels.size()), h(dim)});
}

void write_convergence(io::H5Writer& w, const GsaResult& r, const FeatureResult& f) {
  if (f.convergence_n.empty()) return;
  const std::string g = "/gsa/" + f.name + "/convergence";
  const std::size_t dim = r.parameters.size();
  std::vector<std::int64_t> n(f.convergence_n.begin(), f.convergence_n.end());
  w.write(g + "/n", n, "1");
  if (r.method == "sobol") {
    using Field = std::vector<double> SobolIndices::*;
    const std::pair<const char*, Field> fields[] = {
        {"S1", &SobolIndices::S1}, {"S1_conf", &SobolIndices::S1_conf}, {"ST", &SobolIndices::ST}, {"ST_conf", &SobolIndices::ST_conf}};
    for (const auto& [name, field] : fields) write_rows(w, g + "/" + name, f.sobol_convergence, field, "1", dim);
  } else {
    write_rows(w, g + "/mu_star", f.morris_convergence, &MorrisIndices::mu_star, f.unit, dim);
    write_rows(w, g + "/mu_star_conf", f.morris_convergence, &MorrisIndices::mu_star_conf, f.unit, dim);
    write_rows(w, g + "/sigma", f.morris_convergence, &MorrisIndices::sigma, f.unit, dim);
  }
}

std::vector<std::int64_t> flags(const std::vector<char>& v) { return {v.begin(), v.end()}; }

// <index>_resolved (1 resolved, 0 not) and n_to_resolve (gsa/resolution.hpp).
void write_resolution(io::H5Writer& w, const GsaResult& r, const FeatureResult& f, const std::string& g) {
  const FeatureResolution res = resolve(r, f);
  const hsize_t dim = h(r.parameters.size());
  if (r.method == "sobol") {
    w.write(g + "/S1_resolved", flags(res.S1), "1"), w.write(g + "/ST_resolved", flags(res.ST), "1");
    if (!res.S2.empty()) w.write(g + "/S2_resolved", flags(res.S2), "1", {dim, dim});
  } else {
    w.write(g + "/mu_star_resolved", flags(res.mu_star), "1");
  }
  w.set_attribute(g, "n_unresolved", static_cast<double>(res.n_unresolved));
  w.set_attribute(g, "n_to_resolve", res.n_to_resolve);
}

void write_feature(io::H5Writer& w, const GsaResult& r, const FeatureResult& f) {
  if (f.name.empty() || f.name == "design" || f.name.find('/') != std::string::npos)
    throw Error("gsa: '" + f.name + "' cannot be a feature name in /gsa (empty, 'design' or containing '/')");
  if (f.y.size() * r.parameters.size() != r.unit_design().size())
    throw Error("gsa: feature '" + f.name + "' has " + std::to_string(f.y.size()) + " outputs for a design of " +
                std::to_string(r.unit_design().size() / r.parameters.size()) + " rows");
  const std::string g = "/gsa/" + f.name;
  const hsize_t dim = h(r.parameters.size());
  w.write(g + "/Y", f.y, f.unit);
  if (r.method == "sobol") {
    const SobolIndices& s = f.sobol;
    w.write(g + "/S1", s.S1, "1"), w.write(g + "/S1_conf", s.S1_conf, "1");
    w.write(g + "/ST", s.ST, "1"), w.write(g + "/ST_conf", s.ST_conf, "1");
    if (!s.S2.empty()) w.write(g + "/S2", s.S2, "1", {dim, dim}), w.write(g + "/S2_conf", s.S2_conf, "1", {dim, dim});
    w.set_attribute(g, "variance", s.variance);
    write_counts(w, g, s.counts);
  } else {
    const MorrisIndices& m = f.morris;
    w.write(g + "/mu", m.mu, f.unit), w.write(g + "/mu_star", m.mu_star, f.unit);
    w.write(g + "/mu_star_conf", m.mu_star_conf, f.unit), w.write(g + "/sigma", m.sigma, f.unit);
    write_counts(w, g, m.counts);
  }
  write_resolution(w, r, f, g);
  w.set_attribute(g, "units", f.unit);
  write_convergence(w, r, f);
}

std::size_t count_attr(const io::H5Reader& r, const std::string& path, const std::string& name) {
  return static_cast<std::size_t>(r.read_double_attribute(path, name));
}

OutputCounts read_counts(const io::H5Reader& r, const std::string& g) {
  return {count_attr(r, g, "n_nonfinite"), count_attr(r, g, "n_dropped"), count_attr(r, g, "n_used")};
}

void read_design(const io::H5Reader& r, GsaResult& out) {
  const auto names = r.read_strings("/gsa/design/parameter_names");
  const auto units = r.read_strings("/gsa/design/parameter_units");
  const auto scales = r.read_strings("/gsa/design/scale");
  const auto lower = r.read_doubles("/gsa/design/lower"), upper = r.read_doubles("/gsa/design/upper");
  for (std::size_t j = 0; j < names.size(); ++j) {
    Parameter p;
    p.name = names[j], p.unit = units[j], p.lower = lower[j], p.upper = upper[j], p.log_scale = scales[j] == "log";
    out.parameters.push_back(p);
  }
  const std::vector<double> unit = r.read_doubles("/gsa/design/unit");
  const std::size_t dim = names.size();
  if (out.method == "sobol") {
    SaltelliOptions& o = out.saltelli_options;
    o.n_base = count_attr(r, "/gsa", "N");
    o.second_order = r.read_double_attribute("/gsa", "second_order") != 0;
    o.skip = count_attr(r, "/gsa", "skip");
    o.scramble = r.read_string_attribute("/gsa", "sequence").find("scramble") != std::string::npos;
    o.seed = std::stoull(r.read_string_attribute("/gsa", "seed"));
    out.saltelli = {o.n_base, dim, o.second_order, unit};
  } else {
    MorrisOptions& o = out.morris_options;
    o.trajectories = count_attr(r, "/gsa", "r");
    o.levels = static_cast<int>(r.read_double_attribute("/gsa", "levels"));
    o.pool = count_attr(r, "/gsa", "pool");
    o.seed = std::stoull(r.read_string_attribute("/gsa", "seed"));
    out.morris = {dim, o.trajectories, o.levels, r.read_double_attribute("/gsa", "delta"), unit};
  }
}

// Splits a levels x D dataset back into the rows of `levels`.
template <class Indices>
void read_rows(const io::H5Reader& r, const std::string& path, std::vector<Indices>& levels,
               std::vector<double> Indices::*field, std::size_t dim) {
  const std::vector<double> m = r.read_doubles(path);
  if (m.size() != levels.size() * dim) throw Error(r.path() + ": " + path + " is not one row of D values per subset");
  for (std::size_t k = 0; k < levels.size(); ++k) (levels[k].*field).assign(m.begin() + k * dim, m.begin() + (k + 1) * dim);
}

void read_convergence(const io::H5Reader& r, const GsaResult& res, FeatureResult& f) {
  const std::string g = "/gsa/" + f.name + "/convergence";
  if (!r.exists(g)) return;
  for (double n : r.read_doubles(g + "/n")) f.convergence_n.push_back(static_cast<std::size_t>(n));
  const std::size_t dim = res.parameters.size(), levels = f.convergence_n.size();
  if (res.method == "sobol") {
    f.sobol_convergence.resize(levels);
    read_rows(r, g + "/S1", f.sobol_convergence, &SobolIndices::S1, dim);
    read_rows(r, g + "/S1_conf", f.sobol_convergence, &SobolIndices::S1_conf, dim);
    read_rows(r, g + "/ST", f.sobol_convergence, &SobolIndices::ST, dim);
    read_rows(r, g + "/ST_conf", f.sobol_convergence, &SobolIndices::ST_conf, dim);
  } else {
    f.morris_convergence.resize(levels);
    read_rows(r, g + "/mu_star", f.morris_convergence, &MorrisIndices::mu_star, dim);
    read_rows(r, g + "/mu_star_conf", f.morris_convergence, &MorrisIndices::mu_star_conf, dim);
    read_rows(r, g + "/sigma", f.morris_convergence, &MorrisIndices::sigma, dim);
  }
}

FeatureResult read_feature(const io::H5Reader& r, const GsaResult& res, const std::string& name) {
  const std::string g = "/gsa/" + name;
  FeatureResult f;
  f.name = name;
  f.unit = r.read_string_attribute(g, "units");
  f.y = r.read_doubles(g + "/Y");
  if (res.method == "sobol") {
    SobolIndices& s = f.sobol;
    s.S1 = r.read_doubles(g + "/S1"), s.S1_conf = r.read_doubles(g + "/S1_conf");
    s.ST = r.read_doubles(g + "/ST"), s.ST_conf = r.read_doubles(g + "/ST_conf");
    if (r.exists(g + "/S2")) s.S2 = r.read_doubles(g + "/S2"), s.S2_conf = r.read_doubles(g + "/S2_conf");
    s.variance = r.read_double_attribute(g, "variance");
    s.counts = read_counts(r, g);
  } else {
    MorrisIndices& m = f.morris;
    m.mu = r.read_doubles(g + "/mu"), m.mu_star = r.read_doubles(g + "/mu_star");
    m.mu_star_conf = r.read_doubles(g + "/mu_star_conf"), m.sigma = r.read_doubles(g + "/sigma");
    m.counts = read_counts(r, g);
  }
  read_convergence(r, res, f);
  return f;
}

}  // namespace

void write_gsa_h5(io::H5Writer& w, const GsaResult& r) {
  if (r.method != "sobol" && r.method != "morris")
    throw Error("gsa: method must be \"sobol\" or \"morris\", got \"" + r.method + "\"");
  if (r.parameters.empty()) throw Error("gsa: no parameters to write");
  write_design(w, r);
  write_method_attributes(w, r);
  for (const FeatureResult& f : r.features) write_feature(w, r, f);
}

GsaResult read_gsa_h5(const io::H5Reader& r) {
  if (!r.is_group("/gsa")) throw Error(r.path() + ": no /gsa group (not a gsa result)");
  GsaResult out;
  out.method = r.read_string_attribute("/gsa", "method");
  if (out.method != "sobol" && out.method != "morris")
    throw Error(r.path() + ": /gsa attribute method is \"" + out.method + "\", expected \"sobol\" or \"morris\"");
  read_design(r, out);
  out.bootstrap.confidence = r.read_double_attribute("/gsa", "confidence_level");
  out.bootstrap.resamples = count_attr(r, "/gsa", "bootstrap_resamples");
  out.bootstrap.seed = std::stoull(r.read_string_attribute("/gsa", "bootstrap_seed"));
  if (r.has_attribute("/gsa", "resolution")) out.resolution = r.read_double_attribute("/gsa", "resolution");
  for (const std::string& name : r.children("/gsa"))
    if (name != "design") out.features.push_back(read_feature(r, out, name));
  return out;
}

}  // namespace phasmid::gsa
