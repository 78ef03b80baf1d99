// Fuzz target: phasmid's HDF5 readers on well-formed HDF5 files with hostile content. The input
// is a template choice and a list of edits applied to one of h5_input's seed files (a simulate
// output, a sweep, a shard): a dataset or attribute removed, values replaced (NaN, +-inf, huge,
// negative, denormal, arbitrary bits), an extent or rank changed, numbers turned into strings
// and back, strings replaced by arbitrary bytes, objects added under unexpected names. The file
// is then written through the HDF5 library, so its container is valid and anything found is
// phasmid's own defect; damage to the container itself is h5_input's domain (byte-level, and
// partly HDF5's own: docs/reliability.md, "Fuzzing"). The readers are those of h5_input.
#include <hdf5.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "build_info.hpp"
#include "fuzz_input.hpp"
#include "h5_readers.hpp"
#include "io/h5_file.hpp"

namespace {
using namespace phasmid;

enum class Kind { Group, Doubles, Integers, Strings, DoubleAttribute, StringAttribute };

struct Item {
  Kind kind = Kind::Group;
  std::string path;       // object path; for attributes the object they sit on
  std::string attribute;  // attributes only
  std::vector<hsize_t> dims;
  std::vector<double> numbers;
  std::vector<std::string> strings;
};

bool is_attribute(const Item& it) { return it.kind == Kind::DoubleAttribute || it.kind == Kind::StringAttribute; }

H5T_class_t dataset_class(const io::H5Reader& r, const std::string& path) {
  const hid_t ds = H5Dopen2(r.id(), path.c_str(), H5P_DEFAULT);
  const hid_t type = H5Dget_type(ds);
  const H5T_class_t c = H5Tget_class(type);
  H5Tclose(type);
  H5Dclose(ds);
  return c;
}

herr_t collect_name(hid_t, const char* name, const H5A_info_t*, void* names) {
  static_cast<std::vector<std::string>*>(names)->push_back(name);
  return 0;
}

void load_attributes(const io::H5Reader& r, const std::string& path, std::vector<Item>& items) {
  std::vector<std::string> names;
  H5Aiterate_by_name(r.id(), path.c_str(), H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_name, &names, H5P_DEFAULT);
  for (const auto& n : names) {
    Item a{Kind::StringAttribute, path, n, {}, {}, {}};
    const hid_t attr = H5Aopen_by_name(r.id(), path.c_str(), n.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    const hid_t type = H5Aget_type(attr);
    if (H5Tget_class(type) == H5T_STRING) {
      a.strings = {r.read_string_attribute(path, n)};
    } else {
      a.kind = Kind::DoubleAttribute;
      a.numbers = {r.read_double_attribute(path, n)};
    }
    H5Tclose(type);
    H5Aclose(attr);
    items.push_back(a);
  }
}

void load(const io::H5Reader& r, const std::string& path, std::vector<Item>& items) {
  load_attributes(r, path, items);
  if (r.is_group(path)) {
    items.push_back({Kind::Group, path, "", {}, {}, {}});
    for (const auto& c : r.children(path)) load(r, path == "/" ? "/" + c : path + "/" + c, items);
    return;
  }
  Item d{Kind::Doubles, path, "", r.dims(path), {}, {}};
  const H5T_class_t c = dataset_class(r, path);
  if (c == H5T_STRING) {
    d.kind = Kind::Strings;
    d.strings = r.read_strings(path);
  } else {
    if (c == H5T_INTEGER) d.kind = Kind::Integers;
    d.numbers = r.read_doubles(path);
  }
  items.push_back(d);
}

const std::vector<std::vector<Item>>& templates() {
  static const std::vector<std::vector<Item>> t = [] {
    std::vector<std::vector<Item>> all;
    for (const char* seed : {"simulate.h5", "sweep.h5", "shard.h5"}) {
      io::H5Reader r(std::string(PHASMID_SOURCE_DIR) + "/fuzz/corpus/h5_input/" + seed);
      all.emplace_back();
      load(r, "/", all.back());
    }
    return all;
  }();
  return t;
}

// The fuzz input, consumed front to back; zeros once it is used up.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : p_(data), end_(data + size) {}
  bool empty() const { return p_ == end_; }
  std::uint8_t byte() { return p_ == end_ ? 0 : *p_++; }
  std::size_t below(std::size_t n) { return n == 0 ? 0 : (std::size_t(byte()) << 8 | byte()) % n; }
  double number() {
    static const double special[] = {std::nan(""), std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity(), 0.0, -0.0, 1e308, -1e308, 4.9e-324,
                                     -1.0, 9007199254740993.0, 1e19, -1e19, 0.5, 2.0, 3.0, 1e6};
    const std::uint8_t b = byte();
    if (b < 16 * 8) return special[b % 16];
    std::uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits = bits << 8 | byte();
    double x;
    std::memcpy(&x, &bits, sizeof x);
    return x;
  }
  std::string text() {
    const std::size_t n = byte();
    std::string s;
    for (std::size_t i = 0; i < n && !empty(); ++i) s.push_back(static_cast<char>(byte()));
    return s;
  }

 private:
  const std::uint8_t* p_;
  const std::uint8_t* end_;
};

void resize(Item& it, std::size_t n, Bytes& in) {
  it.dims = {n};
  if (it.kind == Kind::Strings) {
    it.strings.resize(n);
    return;
  }
  while (it.numbers.size() < n) it.numbers.push_back(in.number());
  it.numbers.resize(n);
}

void edit(std::vector<Item>& items, Bytes& in) {
  Item& it = items[in.below(items.size())];
  const bool strings = it.kind == Kind::Strings || it.kind == Kind::StringAttribute;
  switch (in.byte() % 7) {
    case 0: items.erase(items.begin() + (&it - items.data())); return;
    case 1:
      if (strings && !it.strings.empty()) it.strings[in.below(it.strings.size())] = in.text();
      if (!strings && !it.numbers.empty()) it.numbers[in.below(it.numbers.size())] = in.number();
      return;
    case 2:
      if (!is_attribute(it) && it.kind != Kind::Group) resize(it, in.byte() % 40, in);
      return;
    case 3:  // same values, another rank
      if (!is_attribute(it) && it.kind != Kind::Group && it.kind != Kind::Strings) {
        const hsize_t n = it.numbers.size();
        it.dims = in.byte() % 2 ? std::vector<hsize_t>{1, n} : std::vector<hsize_t>{n, 1, 1};
      }
      return;
    case 4:  // numbers <-> strings
      if (it.kind == Kind::Doubles || it.kind == Kind::Integers) {
        it.kind = Kind::Strings;
        it.strings.assign(it.numbers.size(), in.text());
        it.dims = {it.strings.size()};
      } else if (it.kind == Kind::Strings) {
        it.kind = Kind::Doubles;
        it.numbers.assign(it.strings.size(), in.number());
      } else if (it.kind == Kind::StringAttribute) {
        it.kind = Kind::DoubleAttribute;
        it.numbers = {in.number()};
      } else if (it.kind == Kind::DoubleAttribute) {
        it.kind = Kind::StringAttribute;
        it.strings = {in.text()};
      }
      return;
    case 5: {  // a copy under a name the readers do not expect, next to the original
      Item copy = it;
      std::string name = in.text();
      for (char& c : name) c = (c == '/' || c == '.' || c == 0) ? '_' : c;
      if (name.empty()) return;
      if (is_attribute(copy)) copy.attribute = name;
      else copy.path = (copy.path == "/" ? "" : copy.path) + "/" + name;
      items.push_back(copy);
      return;
    }
    default:  // integers become doubles with fractions and the other way round
      if (it.kind == Kind::Integers) it.kind = Kind::Doubles;
      else if (it.kind == Kind::Doubles) it.kind = Kind::Integers;
      return;
  }
}

void write_item(io::H5Writer& w, const Item& it) {
  switch (it.kind) {
    case Kind::Group: w.ensure_group(it.path); return;
    case Kind::Doubles: w.write(it.path, it.numbers, "1", it.dims); return;
    case Kind::Integers: {
      std::vector<std::int64_t> v;
      for (double x : it.numbers) v.push_back(std::isfinite(x) && std::fabs(x) < 9e18 ? static_cast<std::int64_t>(x) : -1);
      w.write(it.path, v, "1", it.dims);
      return;
    }
    case Kind::Strings: w.write(it.path, it.strings); return;
    default: return;  // attributes go on after every object exists
  }
}

// The edited file, written through HDF5; "" if the edits made it unwritable (two objects of
// one name, a dataset where a group should be), which is not a reader's input.
std::string write_file(const std::vector<Item>& items) {
  const std::string path = fuzz::scratch_path("content.h5");
  try {
    io::H5Writer w(path);
    for (const auto& it : items) write_item(w, it);
    for (const auto& it : items) {
      if (it.kind == Kind::StringAttribute) w.set_attribute(it.path, it.attribute, it.strings.at(0));
      if (it.kind == Kind::DoubleAttribute) w.set_attribute(it.path, it.attribute, it.numbers.at(0));
    }
    w.commit();
  } catch (const Error&) {
    return "";
  }
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  std::vector<Item> items = templates()[in.byte() % templates().size()];
  for (int k = 0; k < 32 && !in.empty() && !items.empty(); ++k) edit(items, in);
  const std::string path = write_file(items);
  if (path.empty()) return 0;
  fuzz::read_h5_as_phasmid_does(path);
  std::remove(path.c_str());
  return 0;
}
