// The global-heap check refuses exactly the collections HDF5 1.10 cannot walk, and nothing else.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "io/h5_file.hpp"
#include "io/h5_heap_check.hpp"

using namespace phasmid;

namespace {

std::string write_file_with_strings(const std::string& name) {
  const auto path = (std::filesystem::temp_directory_path() / name).string();
  std::filesystem::remove(path);
  io::H5Writer w(path);
  w.write_run_info({"a = 1\n", "phasmid test"});
  w.write("/parameters/names", std::vector<std::string>{"middle.fti.b_v", "middle.fti.k_spring"});
  w.commit();
  return path;
}

std::vector<char> slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void spit(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::size_t first_collection(const std::vector<char>& bytes) {
  const char sig[] = "GCOL";
  const auto it = std::search(bytes.begin(), bytes.end(), sig, sig + 4);
  return static_cast<std::size_t>(it - bytes.begin());
}

// Rewrites the header of the collection's first object (after the 16-byte collection header)
// as a free-space object (index 0) of `size` bytes.
void make_first_object_free_space(std::vector<char>& bytes, std::size_t collection, std::uint64_t size) {
  char* object = bytes.data() + collection + 16;
  std::memset(object, 0, 2);  // heap object index 0 = free space
  for (int i = 0; i < 8; ++i) object[8 + i] = static_cast<char>((size >> (8 * i)) & 0xff);
}

std::string error_of(const std::string& path) {
  try {
    io::check_global_heaps(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(H5HeapCheck, AcceptsTheFilesPhasmidWrites) {
  const auto path = write_file_with_strings("phasmid_heap_ok.h5");
  ASSERT_LT(first_collection(slurp(path)), slurp(path).size()) << "the file has no global heap";
  EXPECT_NO_THROW(io::check_global_heaps(path));
  io::H5Reader r(path);
  EXPECT_EQ(r.read_strings("/parameters/names")[1], "middle.fti.k_spring");
}

TEST(H5HeapCheck, RefusesAFreeSpaceObjectOfSizeZeroNamingFileAndByte) {
  const auto path = write_file_with_strings("phasmid_heap_stuck.h5");
  auto bytes = slurp(path);
  const std::size_t collection = first_collection(bytes);
  make_first_object_free_space(bytes, collection, 0);
  spit(path, bytes);
  const std::string expected =
      path + ": damaged HDF5 global heap at byte " + std::to_string(collection + 16);
  try {
    io::H5Reader r(path);  // HDF5 itself would loop for ever on the first string read
    FAIL() << "a global heap HDF5 cannot walk was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(expected, 0), 0u) << e.what();
  }
}

TEST(H5HeapCheck, LeavesOtherDamageToHdf5) {
  // A free-space object that does advance the walk is HDF5's to judge (it reports an error or
  // reads garbage strings, but terminates): the check must not refuse it.
  const auto path = write_file_with_strings("phasmid_heap_free.h5");
  auto bytes = slurp(path);
  make_first_object_free_space(bytes, first_collection(bytes), 24);
  spit(path, bytes);
  EXPECT_NO_THROW(io::check_global_heaps(path));
}

TEST(H5HeapCheck, RefusesAnObjectLargerThanItsCollection) {
  // HDF5 would copy the object out with the declared size, reading past the collection.
  const auto path = write_file_with_strings("phasmid_heap_long.h5");
  auto bytes = slurp(path);
  const std::size_t collection = first_collection(bytes);
  char* size = bytes.data() + collection + 16 + 8;  // first object's size field
  size[3] = 0x10;  // + 256 MiB
  spit(path, bytes);
  EXPECT_NE(error_of(path).find(": damaged HDF5 global heap at byte " + std::to_string(collection + 16) +
                                " (an object larger than its collection)"),
            std::string::npos);
}

TEST(H5HeapCheck, RefusesAStringLongerThanTheFileBeforeHdf5AllocatesIt) {
  // A string dataset's descriptor (length, collection, index) with a damaged length: HDF5 would
  // allocate and clear that many bytes (here 4 GB) before it reads the string.
  const auto path = write_file_with_strings("phasmid_heap_descriptor.h5");
  std::size_t start = 0;
  {
    io::H5Reader r(path);
    const hid_t ds = H5Dopen2(r.id(), "/parameters/names", H5P_DEFAULT);
    start = static_cast<std::size_t>(H5Dget_offset(ds));
    H5Dclose(ds);
  }
  auto bytes = slurp(path);
  ASSERT_LT(start + 16, bytes.size());
  std::memset(bytes.data() + start + 16, 0xff, 4);  // element 1's length: 2^32 - 1
  spit(path, bytes);
  // With the rest of the descriptor intact, the scan at open finds it wherever it is stored
  // (attributes too, whose bytes HDF5's API does not give).
  EXPECT_NE(error_of(path).find(": damaged HDF5 global heap at byte " + std::to_string(start + 16) +
                                " (a string declares 4294967295 bytes)"),
            std::string::npos)
      << error_of(path);
  // With its object index damaged too the scan cannot tell it from data; the dataset's own
  // check, which reads the descriptors where the dataset stores them, still refuses it.
  std::memset(bytes.data() + start + 16 + 12, 0x77, 2);
  spit(path, bytes);
  io::H5Reader r(path);
  EXPECT_NO_THROW(r.read_string_attribute("/", "config"));
  try {
    r.read_strings("/parameters/names");
    FAIL() << "a 4 GB string was read";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": dataset /parameters/names: damaged string at element 1 (declares 4294967295 bytes in a " +
                                         std::to_string(bytes.size()) + "-byte file)");
  }
}
