#include "common/error.hpp"
#include "features/features.hpp"
#include "io/h5_file.hpp"

namespace phasmid::features {

void write_features_h5(io::H5Writer& out, const std::vector<Feature>& features) {
  out.ensure_group("/features");
  for (const auto& f : features) out.write_scalar("/features/" + f.name, f.value, f.unit);
}

std::vector<Feature> read_features_h5(const io::H5Reader& in) {
  if (!in.is_group("/features")) throw Error(in.path() + ": no /features group (not a phasmid run file?)");
  std::vector<Feature> out;
  for (const auto& name : in.children("/features")) {
    const std::string path = "/features/" + name;
    if (in.is_group(path)) continue;
    auto d = in.dims(path);
    if (!d.empty() && !(d.size() == 1 && d[0] == 1)) continue;  // scalars only
    std::vector<double> v = in.read_doubles(path);
    if (v.size() != 1) continue;
    std::string unit = "1";
    try {
      unit = in.read_string_attribute(path, "units");
    } catch (const Error&) {
    }
    out.push_back({name, v[0], unit});
  }
  return out;
}

}  // namespace phasmid::features
