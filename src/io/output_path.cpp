#include "io/output_path.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "common/error.hpp"

namespace phasmid::io {
namespace {

const char* kind_name(mode_t m) {
  if (S_ISREG(m)) return "a regular file";
  if (S_ISDIR(m)) return "a directory";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISFIFO(m)) return "a fifo";
  if (S_ISSOCK(m)) return "a socket";
  return "neither a regular file nor a directory";
}

// stat() follows symlinks, so a link to /dev/null is refused like /dev/null itself; a dangling
// link would make the rename replace the link, which is what a new path means.
void check_one(const std::string& path, const std::vector<std::string>& inputs) {
  if (path.empty()) throw Error("output path is empty");
  struct stat out {};
  if (::stat(path.c_str(), &out) != 0) {
    if (errno == ENOENT) return;
    throw Error("output " + path + ": " + std::strerror(errno));
  }
  if (!S_ISREG(out.st_mode))
    throw Error("output " + path + " is " + kind_name(out.st_mode) + "; phasmid writes only new paths or regular files");
  for (const std::string& in : inputs) {
    struct stat st {};
    if (in.empty() || ::stat(in.c_str(), &st) != 0) continue;
    if (st.st_dev == out.st_dev && st.st_ino == out.st_ino)
      throw Error("output " + path + " is the input " + in + "; choose another output path (-o)");
  }
}

}  // namespace

void check_output_path(const std::string& out, const std::vector<std::string>& inputs,
                       const std::vector<std::string>& companions) {
  check_one(out, inputs);
  check_one(out + ".tmp", inputs);
  for (const std::string& c : companions) check_one(c, inputs);
}

void check_output_directory(const std::string& dir) {
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) {
    if (errno == ENOENT) return;
    throw Error("output directory " + dir + ": " + std::strerror(errno));
  }
  if (!S_ISDIR(st.st_mode)) throw Error("output directory " + dir + " is " + kind_name(st.st_mode));
}

}  // namespace phasmid::io
