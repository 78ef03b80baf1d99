#include "io/h5_heap_check.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
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

// The superblock (at 0, 512, 1024, ... after a user block) gives the widths of "offset"
// (address) and "length" fields.
std::pair<int, int> field_widths(RandomAccess& file) {
  static const unsigned char kSuper[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  for (std::uint64_t at = 0; at + 16 <= file.size(); at = at ? at * 2 : 512) {
    unsigned char head[16];
    file.read(at, head, sizeof head);
    if (std::memcmp(head, kSuper, 8) != 0) continue;
    auto valid = [](int w) { return (w == 2 || w == 4 || w == 8) ? w : 8; };
    return head[8] <= 1 ? std::pair{valid(head[13]), valid(head[14])} : std::pair{valid(head[9]), valid(head[10])};
  }
  return {8, 8};
}

// The objects of one collection: index -> size, as HDF5's walk finds them.
using Collection = std::map<std::uint64_t, std::uint64_t>;

struct Damage {
  std::uint64_t offset = 0;  // 0: none
  const char* what = "";
};

// HDF5's walk over one collection (H5HG deserialisation). Finds an object on which that walk
// would not advance, or whose data runs past the collection (HDF5 copies it out with that size,
// reading past its buffer); fills `objects` with what it walked.
Damage damaged_object(RandomAccess& file, std::uint64_t start, int width, Collection& objects) {
  const std::uint64_t header = 8 + static_cast<std::uint64_t>(width);  // "GCOL", version, 3, size
  const std::uint64_t object_header = 8 + static_cast<std::uint64_t>(width);
  if (start + header > file.size() || file.uint(start + 4, 1) != 1) return {};
  const std::uint64_t size = file.uint(start + 8, width);
  if (size < header || size > file.size() - start) return {};  // HDF5 fails its read instead
  const std::uint64_t end = start + size;
  for (std::uint64_t p = start + header; p < end;) {
    if (p + object_header > end) break;  // tail too small for a header: free space
    const std::uint64_t index = file.uint(p, 2);
    const std::uint64_t object_size = file.uint(p + 8, width);
    objects[index] = object_size;
    std::uint64_t need = object_size;
    if (index > 0) {
      if (object_size > end - p - object_header) return {p, "an object larger than its collection"};
      need = object_header + (object_size + kAlignment - 1) / kAlignment * kAlignment;
    }
    if (need == 0) return {p, "an object HDF5 cannot step over"};
    if (need > end - p) break;  // free space running past the end: HDF5 stops its walk there
    p += need;
  }
  return {};
}

// Calls visit(offset, block, n, at) for every block of the file, each read with `overlap` bytes
// of the next one so that a pattern of that length is seen whole in one block.
template <class Visit>
void for_each_block(RandomAccess& file, std::size_t overlap, Visit&& visit) {
  constexpr std::size_t kBlock = 1 << 20;
  std::vector<char> block(kBlock + overlap);
  for (std::uint64_t at = 0; at < file.size(); at += kBlock) {
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(block.size(), file.size() - at));
    file.read(at, block.data(), n);
    visit(block.data(), n, std::min(n, kBlock), at);
  }
}

[[noreturn]] void refuse(const std::string& path, std::uint64_t byte, const std::string& what) {
  throw Error(path + ": damaged HDF5 global heap at byte " + std::to_string(byte) + " (" + what +
              "); the file cannot be read");
}

std::map<std::uint64_t, Collection> walk_collections(RandomAccess& file, int width, const std::string& path) {
  std::map<std::uint64_t, Collection> collections;
  for_each_block(file, sizeof kSignature, [&](const char* b, std::size_t n, std::size_t own, std::uint64_t at) {
    for (const char* it = b; (it = std::search(it, b + n, std::begin(kSignature), std::end(kSignature))) < b + own; ++it) {
      const std::uint64_t offset = at + static_cast<std::uint64_t>(it - b);
      Collection objects;
      if (const Damage d = damaged_object(file, offset, width, objects); d.offset) refuse(path, d.offset, d.what);
      if (!objects.empty()) collections[offset] = std::move(objects);
    }
  });
  return collections;
}

template <std::size_t kWidth>
std::uint64_t little_endian(const char* p) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "HDF5's little-endian fields are read directly");
  std::uint64_t v = 0;
  std::memcpy(&v, p, kWidth);  // one load: this scan visits every byte of the file
  return v;
}

// A variable-length element is stored as (length: 4 bytes, collection address, object index:
// 4 bytes). HDF5 allocates and clears `length` bytes before it reads the object, so a damaged
// length makes it take up to 4 GB for a few-kB file. No string in a file is longer than the
// file: a descriptor that names an object of a collection and declares more is refused.
// A descriptor never lies inside a collection (phasmid writes no variable-length data nested in
// variable-length data), but a collection's own bytes can look like one: a string's last bytes,
// then an object header whose index, read as an address, is that of another collection (object
// 2048 of a large collection and a collection at byte 2048). Those are not refused.
bool inside_collection(RandomAccess& file, const std::map<std::uint64_t, Collection>& collections,
                       std::uint64_t at, int length_width) {
  auto c = collections.upper_bound(at);
  if (c == collections.begin()) return false;
  --c;
  return at < c->first + file.uint(c->first + 8, length_width);  // walk_collections checked the size field fits
}

template <std::size_t kOffsetWidth>
void check_descriptors(RandomAccess& file, const std::map<std::uint64_t, Collection>& collections,
                       const std::string& path, int length_width) {
  constexpr std::size_t kSpan = 4 + kOffsetWidth + 4;
  const std::uint64_t lowest = collections.begin()->first, highest = collections.rbegin()->first;
  for_each_block(file, kSpan, [&](const char* b, std::size_t n, std::size_t own, std::uint64_t at) {
    for (std::size_t i = 0; i < own && i + kSpan <= n; ++i) {
      const std::uint64_t length = little_endian<4>(b + i);
      const std::uint64_t address = little_endian<kOffsetWidth>(b + i + 4);
      if (length <= file.size() || address < lowest || address > highest) continue;
      const auto c = collections.find(address);
      if (c != collections.end() && c->second.count(little_endian<4>(b + i + 4 + kOffsetWidth)) &&
          !inside_collection(file, collections, at + i, length_width))
        refuse(path, at + i, "a string declares " + std::to_string(length) + " bytes");
    }
  });
}

}  // namespace

void check_global_heaps(const std::string& path) {
  RandomAccess file(path);
  const auto [offset_width, length_width] = field_widths(file);
  const auto collections = walk_collections(file, length_width, path);
  if (collections.empty()) return;
  switch (offset_width) {
    case 2: return check_descriptors<2>(file, collections, path, length_width);
    case 4: return check_descriptors<4>(file, collections, path, length_width);
    default: return check_descriptors<8>(file, collections, path, length_width);
  }
}

void check_string_descriptors(hid_t file, hid_t dataset, hsize_t n, const std::string& file_path,
                              const std::string& dataset_path) {
  if (n == 0) return;
  const std::string where = file_path + ": dataset " + dataset_path;
  const haddr_t start = H5Dget_offset(dataset);
  if (start == HADDR_UNDEF) throw Error(where + " is not stored contiguously (phasmid does not write such strings)");
  size_t offset_width = 8, length_width = 8;
  const hid_t fcpl = H5Fget_create_plist(file);
  if (fcpl >= 0) H5Pget_sizes(fcpl, &offset_width, &length_width), H5Pclose(fcpl);
  RandomAccess raw(file_path);
  const std::uint64_t element = 4 + offset_width + 4;  // length, collection address, index
  if (start > raw.size() || n > (raw.size() - start) / element)
    throw Error(where + ": its " + std::to_string(n) + " strings lie beyond the end of the file");
  constexpr hsize_t kPerRead = 4096;  // descriptors per read: one seek per block, not per string
  std::vector<char> block;
  for (hsize_t first = 0; first < n; first += kPerRead) {
    const hsize_t count = std::min(kPerRead, n - first);
    block.resize(static_cast<std::size_t>(count * element));
    raw.read(start + first * element, block.data(), block.size());
    for (hsize_t k = 0; k < count; ++k) {
      const std::uint64_t length = little_endian<4>(block.data() + k * element);
      if (length > raw.size())
        throw Error(where + ": damaged string at element " + std::to_string(first + k) + " (declares " +
                    std::to_string(length) + " bytes in a " + std::to_string(raw.size()) + "-byte file)");
    }
  }
}

}  // namespace phasmid::io
