#include "fit/locomotion_mat.hpp"

#include <matio.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "common/error.hpp"
#include "common/format.hpp"

namespace phasmid::fit {
namespace {

// matio reports problems through a log function that prints by default; phasmid keeps the
// last message for its own one-line error instead.
thread_local std::string matio_message;
void keep_matio_message(int, char* message) { matio_message = message ? message : ""; }

struct MatFile {
  mat_t* mat = nullptr;
  ~MatFile() {
    if (mat) Mat_Close(mat);
  }
};
struct VarDeleter {
  void operator()(matvar_t* v) const { Mat_VarFree(v); }
};
using Var = std::unique_ptr<matvar_t, VarDeleter>;

std::string dims(const matvar_t* v) {
  std::string s;
  for (int i = 0; i < v->rank; ++i) s += (i ? "x" : "") + std::to_string(v->dims[i]);
  return s;
}

size_t elements(const matvar_t* v) {
  size_t n = 1;
  for (int i = 0; i < v->rank; ++i) n *= v->dims[i];
  return n;
}

// Reads one field of a (1x1) struct; the error names the path of the field.
class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)) {}
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw Error(path_ + ": " + field + ": " + what);
  }

  matvar_t* field(matvar_t* s, const std::string& parent, const std::string& name) const {
    if (s->class_type != MAT_C_STRUCT) fail(parent, "is not a struct (cannot hold '" + name + "')");
    if (elements(s) < 1) fail(parent, "is an empty struct array");
    matvar_t* f = Mat_VarGetStructFieldByName(s, name.c_str(), 0);
    if (!f) fail(parent + "." + name, "missing");
    return f;
  }

  // A real numeric array as doubles (column-major, as MATLAB stores it).
  std::vector<double> numbers(matvar_t* v, const std::string& field) const {
    if (v->isComplex) fail(field, "is complex; expected real numbers");
    const size_t n = elements(v);
    if (n > 0 && !v->data) fail(field, "has no data");
    std::vector<double> out(n);
    switch (v->class_type) {
      case MAT_C_DOUBLE: convert<double>(v, out); break;
      case MAT_C_SINGLE: convert<float>(v, out); break;
      case MAT_C_INT8: convert<int8_t>(v, out); break;
      case MAT_C_UINT8: convert<uint8_t>(v, out); break;
      case MAT_C_INT16: convert<int16_t>(v, out); break;
      case MAT_C_UINT16: convert<uint16_t>(v, out); break;
      case MAT_C_INT32: convert<int32_t>(v, out); break;
      case MAT_C_UINT32: convert<uint32_t>(v, out); break;
      case MAT_C_INT64: convert<int64_t>(v, out); break;
      case MAT_C_UINT64: convert<uint64_t>(v, out); break;
      default: fail(field, "is not a numeric array (MATLAB class " + std::to_string(v->class_type) + ")");
    }
    return out;
  }

  std::string text(matvar_t* v, const std::string& field) const {
    if (v->class_type != MAT_C_CHAR || !v->data) fail(field, "is not a character string");
    std::string s;
    const size_t n = elements(v);
    for (size_t i = 0; i < n; ++i) {
      const unsigned c = v->data_type == MAT_T_UINT16 || v->data_type == MAT_T_UTF16
                             ? static_cast<const uint16_t*>(v->data)[i]
                             : static_cast<const uint8_t*>(v->data)[i];
      s += c < 128 ? static_cast<char>(c) : '?';
    }
    return s;
  }

  double scalar(matvar_t* v, const std::string& field, size_t index = 0) const {
    std::vector<double> x = numbers(v, field);
    if (x.size() <= index) fail(field, "has " + std::to_string(x.size()) + " elements; expected at least " + std::to_string(index + 1));
    return x[index];
  }

  // A numeric array of `rows` x `cols` (a vector of `rows` may be a row or a column).
  std::vector<double> matrix(matvar_t* v, const std::string& field, size_t rows, size_t cols) const {
    if (v->class_type < MAT_C_DOUBLE || v->class_type > MAT_C_UINT64)
      fail(field, "is not a numeric array (MATLAB class " + std::to_string(v->class_type) + ")");
    const bool ok = v->rank == 2 && ((v->dims[0] == rows && v->dims[1] == cols) ||
                                     (cols == 1 && v->dims[0] == 1 && v->dims[1] == rows));
    if (!ok)
      fail(field, "is " + dims(v) + "; expected " + std::to_string(rows) + "x" + std::to_string(cols) +
                      (cols == 1 ? " (one value per frame)" : ""));
    return numbers(v, field);
  }

 private:
  template <class T>
  static void convert(const matvar_t* v, std::vector<double>& out) {
    const T* d = static_cast<const T*>(v->data);
    for (size_t i = 0; i < out.size(); ++i) out[i] = static_cast<double>(d[i]);
  }
  std::string path_;
};

Var read_variable(mat_t* mat, const Reader& r, const std::string& name) {
  Var v(Mat_VarRead(mat, name.c_str()));
  if (!v) r.fail(name, "missing (not a Stick Insect Locomotion trial?)");
  return v;
}

void add_channel(KinematicData& d, const Reader& r, std::string name, std::vector<double> x, const std::string& field) {
  bool finite = false;
  for (double a : x) finite = finite || std::isfinite(a);
  if (!finite) r.fail(field, "has no finite angle");
  d.channels.push_back(std::move(name));
  d.angles_deg.push_back(std::move(x));
}

// The ThC angle: the column of cox.angle that ROTSEQ names 'Z'.
void read_leg_angles(KinematicData& d, const Reader& r, matvar_t* leg, const std::string& name, size_t n) {
  matvar_t* cox = r.field(leg, name, "cox");
  const std::string seq = r.text(r.field(cox, name + ".cox", "ROTSEQ"), name + ".cox.ROTSEQ");
  const size_t z = seq.find_first_of("Zz");
  if (seq.size() != 3 || z == std::string::npos || seq.find_first_of("Zz", z + 1) != std::string::npos)
    r.fail(name + ".cox.ROTSEQ", "is '" + seq + "'; expected three rotations with one Z (e.g. ZXY)");
  std::vector<double> a = r.matrix(r.field(cox, name + ".cox", "angle"), name + ".cox.angle", n, 3);
  add_channel(d, r, name + ".thc", std::vector<double>(a.begin() + z * n, a.begin() + (z + 1) * n), name + ".cox.angle");
  for (auto [seg, joint] : {std::pair<const char*, const char*>{"fem", "ctr"}, {"tib", "fti"}}) {
    const std::string f = name + "." + seg;
    add_channel(d, r, name + "." + joint, r.matrix(r.field(r.field(leg, name, seg), f, "angle"), f + ".angle", n, 1), f + ".angle");
  }
}

// contact.<leg>.time: [touchdown, lift-off] frames, one row per stance, in order.
std::vector<features::Stance> read_stances(const Reader& r, matvar_t* contact, const std::string& leg, size_t n, double rate) {
  const std::string f = "contact." + leg + ".time";
  matvar_t* tv = r.field(r.field(contact, "contact", leg), "contact." + leg, "time");
  if (tv->rank != 2 || tv->dims[1] != 2) r.fail(f, "is " + dims(tv) + "; expected K x 2 ([touchdown, lift-off] frames per stance)");
  const size_t k = tv->dims[0];
  std::vector<double> x = r.numbers(tv, f);
  std::vector<features::Stance> s;
  const double nan = std::nan("");
  double last = 0;
  for (size_t i = 0; i < k; ++i) {
    const double td = x[i], lo = x[k + i];
    const std::string row = f + " row " + std::to_string(i + 1);
    for (double v : {td, lo})
      if (std::isfinite(v) && (v < 1 || v > static_cast<double>(n) || v != std::floor(v)))
        r.fail(row, "frame " + format_g(v) + " is not a frame number 1.." + std::to_string(n));
    if (std::isfinite(td) && std::isfinite(lo) && lo < td) r.fail(row, "lift-off frame before its touchdown frame");
    const double first = std::isfinite(td) ? td : lo;
    if (std::isfinite(first) && first < last) r.fail(row, "frames not in time order (contact frames must increase)");
    last = std::isfinite(lo) ? lo : (std::isfinite(td) ? td : last);
    // The event lies between the frame before and the frame given: its time is taken halfway.
    auto ms = [&](double frame) { return (frame - 1.5) / rate * 1000.0; };
    s.push_back({std::isfinite(td) && td > 1 ? ms(td) : nan, std::isfinite(lo) && lo < static_cast<double>(n) ? ms(lo) : nan});
  }
  return s;
}

}  // namespace

const std::vector<std::string>& locomotion_legs() {
  static const std::vector<std::string> legs = {"L1", "L2", "L3", "R1", "R2", "R3"};
  return legs;
}

KinematicData read_locomotion_mat(const std::string& path, const std::vector<std::string>& legs) {
  Mat_LogInitFunc("phasmid", keep_matio_message);
  matio_message.clear();
  const Reader r(path);
  // matio opens files shorter than a MAT header as empty v5 files; they are no trial.
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw Error(path + ": cannot open (no such file or no permission)");
  std::fseek(f, 0, SEEK_END);
  const long size = std::ftell(f);
  std::fclose(f);
  if (size < 128) throw Error(path + ": not a MATLAB file (" + std::to_string(size) + " bytes, shorter than a MAT header)");
  MatFile file;
  file.mat = Mat_Open(path.c_str(), MAT_ACC_RDONLY);
  if (!file.mat) throw Error(path + ": not a MATLAB file (v5 or v7.3)" + (matio_message.empty() ? "" : ": " + matio_message));
  Var experiment = read_variable(file.mat, r, "experiment");
  const double rate = r.scalar(r.field(experiment.get(), "experiment", "FREQUENCY"), "experiment.FREQUENCY");
  if (!(rate > 0) || !std::isfinite(rate)) r.fail("experiment.FREQUENCY", "frame rate " + format_g(rate) + " Hz is not > 0");
  const double frames = r.scalar(r.field(experiment.get(), "experiment", "N_FRAMES"), "experiment.N_FRAMES");
  if (!(frames >= 2) || frames != std::floor(frames) || frames > 1e8)
    r.fail("experiment.N_FRAMES", format_g(frames, 10) + " is not a frame count >= 2");
  const size_t n = static_cast<size_t>(frames);
  KinematicData d;
  d.source = path;
  for (size_t i = 0; i < n; ++i) d.time_ms.push_back(static_cast<double>(i) / rate * 1000.0);
  Var contact = read_variable(file.mat, r, "contact");
  for (const std::string& leg : legs.empty() ? locomotion_legs() : legs) {
    Var v(Mat_VarRead(file.mat, leg.c_str()));
    if (!v) r.fail(leg, "missing (no such leg in this trial)");
    read_leg_angles(d, r, v.get(), leg, n);
    d.stances[leg] = read_stances(r, contact.get(), leg, n, rate);
  }
  return d;
}

}  // namespace phasmid::fit
