#pragma once
// The MPI process session (docs/cluster.md). phasmid initialises MPI only when a launcher
// started it (mpirun, mpiexec, srun: their environment variables say so), with
// MPI_Init_thread(MPI_THREAD_FUNNELED): only the main thread of a rank calls MPI, OpenMP
// threads inside a rank evaluate. Run without a launcher, or built with
// -DPHASMID_WITH_MPI=OFF, there is one rank and nothing of MPI is touched.
#include <string>

namespace phasmid::parallel {

bool mpi_compiled();            // built with PHASMID_WITH_MPI
std::string mpi_description();  // "MPI (Open MPI v4.1.4, ...)" or "no MPI", for --version

// Initialises MPI if compiled in and a launcher's environment is present; idempotent.
// Throws Error if MPI cannot give MPI_THREAD_FUNNELED.
void init(int& argc, char**& argv);
// MPI_Finalize if init() initialised MPI.
void finalize();
// Ends the whole job from any rank (MPI_Abort), e.g. after a fatal error on one rank; plain
// exit without MPI.
[[noreturn]] void abort_job(int code);

int rank();  // 0 without MPI
int size();  // 1 without MPI

// One report for the whole job (docs/cluster.md "Messages and exit status"). Every rank of an
// MPI job calls agree() exactly once before its first MPI work (make_executor() does, with no
// error), or main() does when the verb ended, with the one-line error it ended on ("" if none).
// Ranks meet there (a non-blocking all-reduce, polled with sleeps so that no core spins) and
// learn whether any of them failed; the first failing rank's line and exit code reach rank 0,
// which alone prints it. Every rank then ends normally (MPI_Finalize, non-zero exit): no
// MPI_Abort. Without MPI it only returns what it was given.
struct Agreement {
  bool all_ok = true;
  int code = 0;          // the first failure's exit code (on the failing ranks their own)
  std::string message;   // on rank 0: the first failing rank's line
  int failed_rank = 0;   // that rank
};
Agreement agree(const std::string& error, int code);
bool agreed();  // agree() was called on this rank

// Thrown by make_executor() on a rank that was ready to work when another rank failed before
// any work: main() ends the rank with `code`, rank 0 printing `message`.
struct JobStopped {
  int code;
  std::string message;
  int failed_rank;
};

// RAII for main(): init on construction, finalize on destruction.
struct Session {
  Session(int& argc, char**& argv) { init(argc, argv); }
  ~Session() { finalize(); }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

}  // namespace phasmid::parallel
