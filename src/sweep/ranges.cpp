#include "sweep/ranges.hpp"

#include <cmath>
#include <limits>

#include "io/h5_scalar.hpp"

namespace phasmid::sweep {

std::vector<ParameterRange> one_at_a_time_ranges(const SweepSpec& spec, const std::vector<double>& feature) {
  std::vector<ParameterRange> out;
  std::size_t point = 0;
  for (const SweptParameter& p : spec.parameters) {
    ParameterRange r;
    r.parameter = p.name;
    r.values = p.values;
    r.lower = r.upper = std::numeric_limits<double>::quiet_NaN();
    int runs = 0;
    for (std::size_t k = 0; k < p.values.size(); ++k, ++point) {
      const int in = feature[point] == 1.0 ? 1 : 0;
      r.in_range.push_back(in);
      if (!in) continue;
      if (std::isnan(r.lower)) r.lower = p.values[k];
      r.upper = p.values[k];
      if (k == 0 || !r.in_range[k - 1]) ++runs;
    }
    r.contiguous = runs == 1;
    out.push_back(std::move(r));
  }
  return out;
}

void write_ranges_h5(io::H5Writer& w, const std::string& feature, const std::vector<ParameterRange>& ranges) {
  w.ensure_group("/sweep/ranges");
  w.set_attribute("/sweep/ranges", "feature", feature);
  for (const ParameterRange& r : ranges) {
    const std::string g = "/sweep/ranges/" + r.parameter;
    w.write(g + "/values", r.values, "see /sweep/parameter_units");
    w.write(g + "/in_range", std::vector<double>(r.in_range.begin(), r.in_range.end()), "1");
    w.write_scalar(g + "/lower", r.lower, "see /sweep/parameter_units");
    w.write_scalar(g + "/upper", r.upper, "see /sweep/parameter_units");
    w.write_scalar(g + "/contiguous", r.contiguous ? 1.0 : 0.0, "1");
  }
}

std::vector<ParameterRange> read_ranges_h5(const io::H5Reader& in) {
  std::vector<ParameterRange> out;
  if (!in.exists("/sweep/ranges")) return out;
  for (const std::string& name : in.children("/sweep/ranges")) {
    const std::string g = "/sweep/ranges/" + name;
    ParameterRange r;
    r.parameter = name;
    r.values = in.read_doubles(g + "/values");
    for (double v : in.read_doubles(g + "/in_range")) r.in_range.push_back(v == 1.0 ? 1 : 0);
    r.lower = io::read_scalar(in, g + "/lower");
    r.upper = io::read_scalar(in, g + "/upper");
    r.contiguous = io::read_scalar(in, g + "/contiguous") == 1.0;
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace phasmid::sweep
