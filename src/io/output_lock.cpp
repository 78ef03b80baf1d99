#include "io/output_lock.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "common/error.hpp"

namespace phasmid::io {
namespace {

// Outputs locked by this process: which thread holds each, and its lock.
std::mutex g_registry_mutex;
std::map<std::string, std::pair<std::thread::id, OutputLock*>> g_registry;
std::function<void()> g_test_hook;

std::string registry_key(const std::string& out) {
  std::error_code ec;
  auto abs = std::filesystem::absolute(out, ec);
  return ec ? out : abs.lexically_normal().string();
}

Error busy(const std::string& out) {
  return Error("output " + out + " is being written by another phasmid process (" + out +
               ".tmp is locked); wait for it or choose another output path (-o)");
}

// A write lock on the whole file, owned by the open file description (not the process).
bool ofd_lock(int fd) {
  struct flock fl {};
  fl.l_type = F_WRLCK;
  fl.l_whence = SEEK_SET;
  fl.l_start = 0;
  fl.l_len = 0;
  return ::fcntl(fd, F_OFD_SETLK, &fl) == 0;
}

// Creates the output's missing directories; returns them, deepest first.
std::vector<std::string> make_parent_directories(const std::string& out) {
  std::vector<std::string> made;
  std::error_code ec;
  for (auto dir = std::filesystem::path(out).parent_path(); !dir.empty() && !std::filesystem::exists(dir, ec);
       dir = dir.parent_path())
    made.push_back(dir.string());
  for (auto it = made.rbegin(); it != made.rend(); ++it)
    if (!std::filesystem::create_directory(*it, ec) && ec)
      throw Error("cannot create directory " + *it + " for " + out + ": " + ec.message());
  return made;
}

void remove_empty_directories(const std::vector<std::string>& dirs) {
  for (const std::string& d : dirs)
    if (::rmdir(d.c_str()) != 0) return;  // not empty: the output is in it
}

// A new descriptor of `tmp` with the lock, -1 if it is locked by someone else.
int open_locked(const std::string& out, const std::string& tmp, int extra_flags) {
  const int fd = ::open(tmp.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | extra_flags, 0644);
  if (fd < 0) {
    if (errno == EEXIST) return -1;  // O_EXCL: another run created it since
    throw Error("cannot create " + tmp + " for " + out + ": " + std::strerror(errno));
  }
  if (g_test_hook) g_test_hook();
  if (ofd_lock(fd)) return fd;
  const int e = errno;
  ::close(fd);
  if (e == EAGAIN || e == EACCES) return -1;
  throw Error("cannot lock " + tmp + " for " + out + ": " + std::strerror(e));
}

}  // namespace

OutputLock::OutputLock(const std::string& out) : out_(out), tmp_(out + ".tmp"), key_(registry_key(out)) {
  {
    std::lock_guard<std::mutex> guard(g_registry_mutex);
    if (g_registry.count(key_))
      throw Error("output " + out + " is being written by another run of this process; wait for it or choose another output path");
    g_registry[key_] = {std::this_thread::get_id(), this};
  }
  try {
    made_dirs_ = make_parent_directories(out);
    // A previous holder renames or removes the file while still holding it, so the inode we
    // locked may no longer be "<out>.tmp": then open the name again.
    for (int attempt = 0; attempt < 1000 && fd_ < 0; ++attempt) {
      fd_ = open_locked(out_, tmp_, 0);
      if (fd_ < 0) throw busy(out_);
      if (!still_named()) ::close(fd_), fd_ = -1;
    }
    if (fd_ < 0) throw Error("output " + out_ + ": " + tmp_ + " keeps being replaced by another process");
  } catch (...) {
    remove_empty_directories(made_dirs_);
    std::lock_guard<std::mutex> guard(g_registry_mutex);
    g_registry.erase(key_);
    throw;
  }
}

OutputLock::~OutputLock() {
  if (still_named()) ::unlink(tmp_.c_str());  // under the lock: no one else may be using it
  ::close(fd_);
  remove_empty_directories(made_dirs_);  // a run that wrote nothing leaves no directory either
  std::lock_guard<std::mutex> guard(g_registry_mutex);
  g_registry.erase(key_);
}

bool OutputLock::still_named() const {
  struct stat held {}, named {};
  return ::fstat(fd_, &held) == 0 && ::stat(tmp_.c_str(), &named) == 0 && held.st_dev == named.st_dev &&
         held.st_ino == named.st_ino;
}

void OutputLock::keep() {
  if (still_named()) return;
  // O_EXCL: if the name exists again, another run made it after our rename and holds it now.
  const int fd = open_locked(out_, tmp_, O_EXCL);
  if (fd < 0) throw busy(out_);
  ::close(fd_);
  fd_ = fd;
}

void OutputLock::publish(bool keep_holding) {
  auto rename_or_throw = [&](const std::string& from) {
    if (std::rename(from.c_str(), out_.c_str()) != 0)
      throw Error("cannot rename " + tmp_ + " to " + out_ + ": " + std::strerror(errno));
  };
  if (!keep_holding) return rename_or_throw(tmp_);
  // "<out>.tmp.next" is ours while we hold the output: no other run writes beside a held output.
  const std::string next = tmp_ + ".next";
  const int fd = ::open(next.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd >= 0 && ofd_lock(fd) && ::renameat2(AT_FDCWD, tmp_.c_str(), AT_FDCWD, next.c_str(), RENAME_EXCHANGE) == 0) {
    ::close(fd_);
    fd_ = fd;  // the new, empty "<out>.tmp"
    if (std::rename(next.c_str(), out_.c_str()) != 0) {
      const int e = errno;
      ::unlink(next.c_str());
      throw Error("cannot rename " + tmp_ + " to " + out_ + ": " + std::strerror(e));
    }
    return;
  }
  if (fd >= 0) ::close(fd), ::unlink(next.c_str());
  rename_or_throw(tmp_);
  try {
    keep();
  } catch (const Error&) {  // another run took the name in this instant: our next write is refused
  }
}

OutputLock* OutputLock::held_by_this_thread(const std::string& out) {
  std::lock_guard<std::mutex> guard(g_registry_mutex);
  auto it = g_registry.find(registry_key(out));
  if (it == g_registry.end() || it->second.first != std::this_thread::get_id()) return nullptr;
  return it->second.second;
}

HeldOutputLock::HeldOutputLock(const std::string& out) : lock_(OutputLock::held_by_this_thread(out)) {
  if (lock_) {
    lock_->keep();
    return;
  }
  own_ = std::make_unique<OutputLock>(out);
  lock_ = own_.get();
}

void set_output_lock_test_hook(std::function<void()> between_open_and_lock) {
  g_test_hook = std::move(between_open_and_lock);
}

}  // namespace phasmid::io
