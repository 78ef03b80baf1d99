#pragma once
// One writer per output (docs/reliability.md, "Two writers"): every run that writes OUT first
// locks "<OUT>.tmp" and holds it until its final rename, so a second run on the same output is
// refused before it creates, truncates or removes any file of it (OUT, OUT.tmp, the sweep
// journal, a continuation's .partial).
//
// The lock is an open-file-description lock (fcntl F_OFD_SETLK) on "<OUT>.tmp", opened without
// truncation. Not flock(): HDF5 1.10 flock()s the files it opens itself. Not a POSIX record lock:
// that would be dropped when HDF5 closes its own descriptor of the same file. The file is
// created if missing; after locking, the locked inode must still be the one named "<OUT>.tmp"
// (a previous holder may have renamed it onto OUT or removed it in between), else it retries.
//
// Within one process a registry refuses a second lock on the same output from another thread
// (two Python threads saving to one path); a writer (io::H5Writer, the report) on the thread
// that holds the lock uses it instead of taking its own (OutputLock::held_by_this_thread).
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace phasmid::io {

class OutputLock {
 public:
  // Locks "<out>.tmp" or throws phasmid::Error in one line ("output OUT is being written by
  // another phasmid process ..."), having created, truncated or removed nothing. Creates the
  // output's missing directories (removed again with the lock if still empty).
  explicit OutputLock(const std::string& out);
  // Removes "<out>.tmp" if it is still the locked file (a run that failed or did not write it),
  // then unlocks.
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;  // the registry points at it
  OutputLock& operator=(const OutputLock&) = delete;

  const std::string& output() const { return out_; }
  const std::string& tmp_path() const { return tmp_; }

  // Renames the finished "<out>.tmp" onto <out>. With `keep_holding`, the lock moves to a new,
  // empty "<out>.tmp" first (made as "<out>.tmp.next", a name no other run uses while the
  // output is held) and the two names are exchanged atomically (renameat2 RENAME_EXCHANGE),
  // so that no instant leaves "<out>.tmp" unlocked for another run; where the
  // file system cannot exchange names, it renames, then keep()s. Throws "cannot rename ...".
  void publish(bool keep_holding);

  // After "<out>.tmp" was renamed onto <out> (or removed) by this holder: locks a new, empty
  // "<out>.tmp" at once, so that the output stays this run's for a further write (gsa writes
  // the sweep, then the analysis). Nothing to do while the locked file is still "<out>.tmp".
  // Throws the refusal if another run took the name in between.
  void keep();

  // The lock on `out` this thread holds, or nullptr.
  static OutputLock* held_by_this_thread(const std::string& out);

 private:
  bool still_named() const;  // the locked inode is the one "<out>.tmp" names
  std::string out_, tmp_, key_;
  std::vector<std::string> made_dirs_;  // the output's directories this lock created
  int fd_ = -1;
};

// The lock this thread already holds on `out` (taken by the verb before any work), or else a
// new one held for the lifetime of this object: what every writer of an output goes through.
class HeldOutputLock {
 public:
  explicit HeldOutputLock(const std::string& out);
  OutputLock& get() { return *lock_; }
  bool owned() const { return own_ != nullptr; }  // taken here, released with this object

 private:
  std::unique_ptr<OutputLock> own_;
  OutputLock* lock_ = nullptr;
};

// Tests only: called between the open and the lock of "<out>.tmp" (to stage the races the
// inode check is for). Empty by default.
void set_output_lock_test_hook(std::function<void()> between_open_and_lock);

}  // namespace phasmid::io
