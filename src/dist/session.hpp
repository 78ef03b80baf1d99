#pragma once
// The MPI process session (docs/cluster.md). phasmid initialises MPI only when a launcher
// started it (mpirun, mpiexec, srun: their environment variables say so), with
// MPI_Init_thread(MPI_THREAD_FUNNELED): only the main thread of a rank calls MPI, OpenMP
// threads inside a rank evaluate. Run without a launcher, or built with
// -DPHASMID_WITH_MPI=OFF, there is one rank and nothing of MPI is touched.
#include <string>

namespace phasmid::dist {

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

// RAII for main(): init on construction, finalize on destruction.
struct Session {
  Session(int& argc, char**& argv) { init(argc, argv); }
  ~Session() { finalize(); }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

}  // namespace phasmid::dist
