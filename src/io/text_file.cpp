#include "io/text_file.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/error.hpp"

namespace phasmid::io {

std::string read_text_file(const std::string& path, const std::string& what) {
  const std::string prefix = path + ": cannot read " + what + ": ";
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw Error(prefix + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw Error(prefix + "not a regular file");
  if (static_cast<std::uintmax_t>(st.st_size) > kMaxTextInputBytes)
    throw Error(prefix + std::to_string(st.st_size) + " bytes, more than the limit of " +
                std::to_string(kMaxTextInputBytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(prefix + std::strerror(errno));
  std::string text(static_cast<size_t>(st.st_size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<size_t>(in.gcount()));  // a file that shrank meanwhile
  if (in.bad()) throw Error(prefix + "read error");
  return text;
}

}  // namespace phasmid::io
