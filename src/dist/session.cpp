#include "dist/session.hpp"

#include <cstdlib>

#include "common/error.hpp"

#ifdef PHASMID_WITH_MPI
#include <mpi.h>
#endif

namespace phasmid::dist {
namespace {
bool g_initialised = false;
int g_rank = 0, g_size = 1;

// Environment variables set by the launchers of Open MPI, MPICH/Hydra, Intel MPI and SLURM's
// PMI/PMIx plug-ins for every rank they start.
bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "PMI_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(v)) return true;
  return false;
}
}  // namespace

bool mpi_compiled() {
#ifdef PHASMID_WITH_MPI
  return true;
#else
  return false;
#endif
}

std::string mpi_description() {
#ifdef PHASMID_WITH_MPI
  char lib[MPI_MAX_LIBRARY_VERSION_STRING];
  int len = 0;
  MPI_Get_library_version(lib, &len);
  std::string s(lib, static_cast<std::size_t>(len));
  if (auto nl = s.find_first_of("\n,"); nl != std::string::npos) s.resize(nl);
  return "MPI compiled in (" + s + ")";
#else
  return "MPI not compiled in (-DPHASMID_WITH_MPI=OFF)";
#endif
}

void init(int& argc, char**& argv) {
#ifdef PHASMID_WITH_MPI
  if (g_initialised || !launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  g_initialised = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
  if (provided < MPI_THREAD_FUNNELED) throw Error("MPI: the library does not provide MPI_THREAD_FUNNELED");
#else
  (void)argc;
  (void)argv;
#endif
}

void finalize() {
#ifdef PHASMID_WITH_MPI
  if (!g_initialised) return;
  g_initialised = false;
  MPI_Finalize();
#endif
}

void abort_job(int code) {
#ifdef PHASMID_WITH_MPI
  if (g_initialised && g_size > 1) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

int rank() { return g_rank; }
int size() { return g_size; }

}  // namespace phasmid::dist
