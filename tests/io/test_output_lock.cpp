// One writer per output (io::OutputLock, docs/reliability.md "Two writers"): a second writer
// is refused before it touches any file of the output; the lock follows "<out>.tmp" by inode;
// within one process a second thread is refused; a failed holder removes its .tmp.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>

#include "common/error.hpp"
#include "io/h5_file.hpp"
#include "io/output_lock.hpp"

namespace fs = std::filesystem;
using phasmid::Error;
using phasmid::io::H5Reader;
using phasmid::io::H5Writer;
using phasmid::io::HeldOutputLock;
using phasmid::io::OutputLock;

namespace {
struct TempDir {
  fs::path p = fs::temp_directory_path() / ("phasmid_output_lock_" + std::to_string(::getpid()));
  TempDir() {
    fs::remove_all(p);
    fs::create_directories(p);
  }
  ~TempDir() {
    phasmid::io::set_output_lock_test_hook({});
    fs::remove_all(p);
  }
};

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string contents(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// What another process holding the output looks like: an open file description with the lock.
struct ForeignHolder {
  int fd = -1;
  explicit ForeignHolder(const fs::path& tmp, const std::string& text = "") {
    fd = ::open(tmp.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    struct flock fl {};
    fl.l_type = F_WRLCK;
    fl.l_whence = SEEK_SET;
    EXPECT_EQ(::fcntl(fd, F_OFD_SETLK, &fl), 0);
    if (!text.empty()) {
      EXPECT_EQ(::write(fd, text.data(), text.size()), static_cast<ssize_t>(text.size()));
    }
  }
  ~ForeignHolder() { ::close(fd); }
};

bool locked_by_someone(const fs::path& tmp) {
  int fd = ::open(tmp.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return false;
  struct flock fl {};
  fl.l_type = F_WRLCK;
  fl.l_whence = SEEK_SET;
  const bool busy = ::fcntl(fd, F_OFD_GETLK, &fl) == 0 && fl.l_type != F_UNLCK;
  ::close(fd);
  return busy;
}
}  // namespace

TEST(OutputLock, ASecondWriterIsRefusedWithoutTouchingTheFiles) {
  TempDir d;
  const fs::path out = d.p / "out.h5", tmp = d.p / "out.h5.tmp";
  { std::ofstream(out) << "the finished file"; }
  ForeignHolder holder(tmp, "the running writer's bytes");
  const auto mtime = fs::last_write_time(tmp);
  const std::string e = error_of([&] { OutputLock lock(out.string()); });
  EXPECT_EQ(e, "output " + out.string() + " is being written by another phasmid process (" + tmp.string() +
                   " is locked); wait for it or choose another output path (-o)");
  EXPECT_EQ(contents(tmp), "the running writer's bytes");
  EXPECT_EQ(fs::last_write_time(tmp), mtime);
  EXPECT_EQ(contents(out), "the finished file");
  // H5Writer goes through the same lock: refused before HDF5 truncates the .tmp
  EXPECT_NE(error_of([&] { H5Writer w(out.string()); }).find("being written by another phasmid process"), std::string::npos);
  EXPECT_EQ(contents(tmp), "the running writer's bytes");
  EXPECT_EQ(std::distance(fs::directory_iterator(d.p), fs::directory_iterator()), 2);
}

TEST(OutputLock, TheLockedFileMustStillBeNamedTmpElseItRetries) {
  TempDir d;
  const fs::path out = d.p / "out.h5", tmp = d.p / "out.h5.tmp";
  { std::ofstream(tmp) << "the previous holder's finished bytes"; }
  // The previous holder renames its .tmp onto OUT between our open and our lock.
  int calls = 0;
  phasmid::io::set_output_lock_test_hook([&] {
    if (calls++ == 0) fs::rename(tmp, out);
  });
  {
    OutputLock lock(out.string());
    EXPECT_EQ(calls, 2) << "the renamed inode was locked, found stale and the name opened again";
    EXPECT_TRUE(fs::exists(tmp));
    EXPECT_TRUE(locked_by_someone(tmp));
    EXPECT_EQ(contents(out), "the previous holder's finished bytes");
  }
  EXPECT_FALSE(fs::exists(tmp)) << "an unused .tmp is removed by its holder";
  EXPECT_EQ(contents(out), "the previous holder's finished bytes");
}

TEST(OutputLock, AWriterThatLocksBetweenOurOpenAndLockWinsAndKeepsItsFile) {
  TempDir d;
  const fs::path out = d.p / "out.h5", tmp = d.p / "out.h5.tmp";
  std::unique_ptr<ForeignHolder> other;
  phasmid::io::set_output_lock_test_hook([&] { other = std::make_unique<ForeignHolder>(tmp, "theirs"); });
  EXPECT_NE(error_of([&] { OutputLock lock(out.string()); }).find("being written by another phasmid process"),
            std::string::npos);
  EXPECT_EQ(contents(tmp), "theirs");
  EXPECT_FALSE(fs::exists(out));
}

TEST(OutputLock, ASecondThreadOfTheProcessIsRefusedAndTheHoldersThreadReusesTheLock) {
  TempDir d;
  const std::string out = (d.p / "out.h5").string();
  OutputLock lock(out);
  std::string e;
  std::thread([&] { e = error_of([&] { H5Writer w(out); }); }).join();
  EXPECT_EQ(e, "output " + out + " is being written by another run of this process; wait for it or choose another output path");
  std::thread([&] { e = error_of([&] { OutputLock again((d.p / "." / "out.h5").string()); }); }).join();
  EXPECT_NE(e.find("being written"), std::string::npos) << "the same file by another spelling";
  EXPECT_NE(error_of([&] { OutputLock again(out); }).find("being written"), std::string::npos)
      << "a second lock is refused on the holder's thread too";
  HeldOutputLock held(out);
  EXPECT_FALSE(held.owned());
  EXPECT_EQ(&held.get(), &lock);
}

TEST(OutputLock, AFailedHolderRemovesItsTmpAndReleases) {
  TempDir d;
  const std::string out = (d.p / "out.h5").string(), tmp = out + ".tmp";
  {
    OutputLock lock(out);
    {
      H5Writer w(out);  // HDF5 truncates and writes the locked file from the same process
      w.write_scalar("/x", 1.0, "1");
      EXPECT_TRUE(locked_by_someone(tmp));
    }  // not committed
    EXPECT_FALSE(fs::exists(tmp));
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(tmp));
  {  // a holder that never wrote its .tmp
    OutputLock lock(out);
    EXPECT_TRUE(fs::exists(tmp));
  }
  EXPECT_FALSE(fs::exists(tmp));
  OutputLock again(out);  // released: the next writer gets it
}

TEST(OutputLock, ACallersLockOutlastsACommitForTheNextWrite) {
  TempDir d;
  const std::string out = (d.p / "out.h5").string(), tmp = out + ".tmp";
  {
    OutputLock lock(out);
    {
      H5Writer w(out);
      w.write_scalar("/x", 1.0, "1");
      w.commit();
    }
    EXPECT_TRUE(fs::exists(out));
    EXPECT_TRUE(locked_by_someone(tmp)) << "a new .tmp is held at once after the rename";
    EXPECT_EQ(fs::file_size(tmp), 0u);
    EXPECT_FALSE(fs::exists(tmp + ".next")) << "the name the new .tmp was made under";
    {
      H5Reader first(out);
      H5Writer w(out);  // the second write (gsa's analysis) under the same lock
      w.write_scalar("/x", 2.0, "1");
      w.commit();
    }
  }
  EXPECT_FALSE(fs::exists(tmp));
  EXPECT_EQ(H5Reader(out).read_doubles("/x"), std::vector<double>{2.0});
}

TEST(OutputLock, AWriterWithoutACallersLockTakesAndReleasesItsOwn) {
  TempDir d;
  const std::string out = (d.p / "sub" / "out.h5").string();
  {
    H5Writer w(out);
    EXPECT_TRUE(locked_by_someone(out + ".tmp"));
    w.commit();
  }
  EXPECT_FALSE(fs::exists(out + ".tmp"));
  OutputLock after(out);
}
