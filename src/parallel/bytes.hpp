#pragma once
// Byte strings for task inputs and results crossing ranks: fixed-width integers and doubles
// copied bit for bit (every rank of a job runs the same binary on the same architecture), and
// length-prefixed strings and vectors. ByteReader throws Error on a truncated message.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "common/error.hpp"

namespace phasmid::parallel {

class ByteWriter {
 public:
  ByteWriter& u64(std::uint64_t v) { return raw(&v, sizeof v); }
  ByteWriter& f64(double v) { return raw(&v, sizeof v); }
  ByteWriter& str(const std::string& s) {
    u64(s.size());
    buf_ += s;
    return *this;
  }
  ByteWriter& f64s(const std::vector<double>& v) {
    u64(v.size());
    return raw(v.data(), v.size() * sizeof(double));
  }
  ByteWriter& strs(const std::vector<std::string>& v) {
    u64(v.size());
    for (auto& s : v) str(s);
    return *this;
  }
  std::string take() { return std::move(buf_); }

 private:
  ByteWriter& raw(const void* p, std::size_t n) {
    buf_.append(static_cast<const char*>(p), n);
    return *this;
  }
  std::string buf_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : s_(bytes) {}
  std::uint64_t u64() { return get<std::uint64_t>(); }
  double f64() { return get<double>(); }
  std::string str() {
    const std::size_t n = count(1);
    std::string out = s_.substr(pos_, n);
    pos_ += n;
    return out;
  }
  std::vector<double> f64s() {
    std::vector<double> v(count(sizeof(double)));
    if (!v.empty()) std::memcpy(v.data(), s_.data() + pos_, v.size() * sizeof(double));
    pos_ += v.size() * sizeof(double);
    return v;
  }
  std::vector<std::string> strs() {
    std::vector<std::string> v(count(sizeof(std::uint64_t)));
    for (auto& s : v) s = str();
    return v;
  }

 private:
  template <class T>
  T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, s_.data() + pos_, sizeof v);
    pos_ += sizeof v;
    return v;
  }
  std::size_t count(std::size_t unit) {  // a length prefix, checked against what is left
    const std::uint64_t n = u64();
    if (n > (s_.size() - pos_) / unit) throw Error("internal: truncated task message");
    return static_cast<std::size_t>(n);
  }
  void need(std::size_t n) const {
    if (s_.size() - pos_ < n) throw Error("internal: truncated task message");
  }
  const std::string& s_;
  std::size_t pos_ = 0;
};

}  // namespace phasmid::parallel
