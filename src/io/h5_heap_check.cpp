#include "io/h5_heap_check.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

#include "common/error.hpp"

namespace phasmid::io {
namespace {

constexpr char kSignature[] = {'G', 'C', 'O', 'L'};
constexpr std::uint64_t kAlignment = 8;  // H5HG_ALIGNMENT

class RandomAccess {
 public:
  explicit RandomAccess(const std::string& path) : in_(path, std::ios::binary), path_(path) {
    if (!in_) throw Error(path + ": cannot open for reading");
    in_.seekg(0, std::ios::end);
    size_ = static_cast<std::uint64_t>(in_.tellg());
  }
  std::uint64_t size() const { return size_; }
  // Little-endian unsigned of `width` bytes at `offset`; the caller keeps offset + width <= size.
  std::uint64_t uint(std::uint64_t offset, int width) {
    unsigned char b[8] = {};
    read(offset, b, static_cast<std::size_t>(width));
    std::uint64_t v = 0;
    for (int i = width - 1; i >= 0; --i) v = (v << 8) | b[i];
    return v;
  }
  void read(std::uint64_t offset, void* into, std::size_t n) {
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(offset));
    in_.read(static_cast<char*>(into), static_cast<std::streamsize>(n));
    if (in_.gcount() != static_cast<std::streamsize>(n)) throw Error(path_ + ": read error");
  }

 private:
  std::ifstream in_;
  std::string path_;
  std::uint64_t size_ = 0;
};

// The superblock (at 0, 512, 1024, ... after a user block) gives the width of "length" fields.
int length_width(RandomAccess& file) {
  static const unsigned char kSuper[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  for (std::uint64_t at = 0; at + 16 <= file.size(); at = at ? at * 2 : 512) {
    unsigned char head[16];
    file.read(at, head, sizeof head);
    if (std::memcmp(head, kSuper, 8) != 0) continue;
    const int width = head[8] <= 1 ? head[14] : head[10];
    return (width == 2 || width == 4 || width == 8) ? width : 8;
  }
  return 8;
}

// HDF5's walk over one collection (H5HG deserialisation). Returns the offset of an object on
// which that walk would not advance, or 0.
std::uint64_t stuck_object(RandomAccess& file, std::uint64_t start, int width) {
  const std::uint64_t header = 8 + static_cast<std::uint64_t>(width);  // "GCOL", version, 3, size
  const std::uint64_t object_header = 8 + static_cast<std::uint64_t>(width);
  if (start + header > file.size() || file.uint(start + 4, 1) != 1) return 0;
  const std::uint64_t size = file.uint(start + 8, width);
  if (size < header || size > file.size() - start) return 0;  // HDF5 fails its read instead
  const std::uint64_t end = start + size;
  for (std::uint64_t p = start + header; p < end;) {
    if (p + object_header > end) break;  // tail too small for a header: free space
    const std::uint64_t index = file.uint(p, 2);
    const std::uint64_t object_size = file.uint(p + 8, width);
    std::uint64_t need = object_size;
    if (index > 0) {
      if (object_size > UINT64_MAX - object_header - kAlignment) return p;  // wraps around
      need = object_header + (object_size + kAlignment - 1) / kAlignment * kAlignment;
    }
    if (need == 0 || need > UINT64_MAX - p) return p;
    p += need;
  }
  return 0;
}

}  // namespace

void check_global_heaps(const std::string& path) {
  RandomAccess file(path);
  const int width = length_width(file);
  constexpr std::size_t kBlock = 1 << 20;
  std::vector<char> block(kBlock + sizeof kSignature);
  for (std::uint64_t at = 0; at < file.size(); at += kBlock) {
    const std::size_t n = static_cast<std::size_t>(
        std::min<std::uint64_t>(block.size(), file.size() - at));  // overlaps the next block by 4
    file.read(at, block.data(), n);
    for (auto it = block.begin(); it != block.begin() + static_cast<std::ptrdiff_t>(n);) {
      it = std::search(it, block.begin() + static_cast<std::ptrdiff_t>(n), std::begin(kSignature),
                       std::end(kSignature));
      if (it == block.begin() + static_cast<std::ptrdiff_t>(n)) break;
      const std::uint64_t offset = at + static_cast<std::uint64_t>(it - block.begin());
      if (offset - at < kBlock) {  // a match in the overlap is the next block's
        if (const std::uint64_t bad = stuck_object(file, offset, width))
          throw Error(path + ": damaged HDF5 global heap at byte " + std::to_string(bad) +
                      " (an object HDF5 cannot step over); the file cannot be read");
      }
      ++it;
    }
  }
}

}  // namespace phasmid::io
