#include "parallel/session.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <thread>

#include "common/error.hpp"

#ifdef PHASMID_WITH_MPI
#include <mpi.h>
#endif

namespace phasmid::parallel {
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

namespace {
bool g_agreed = false;
}

bool agreed() { return g_agreed; }

#ifdef PHASMID_WITH_MPI
namespace {
constexpr int kAgreeTag = 99;  // the failing rank's line to rank 0; no other message uses it

// MPI_Iallreduce, polled with a growing sleep: Open MPI's blocking collectives spin.
int all_min(int value) {
  int result = value;
  MPI_Request req;
  MPI_Iallreduce(&value, &result, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &req);
  auto wait = std::chrono::microseconds(20);
  for (int done = 0; MPI_Test(&req, &done, MPI_STATUS_IGNORE), !done;) {
    std::this_thread::sleep_for(wait);
    wait = std::min(wait * 2, std::chrono::microseconds(2000));
  }
  return result;
}
}  // namespace
#endif

Agreement agree(const std::string& error, int code) {
  Agreement a;
  a.all_ok = error.empty();
  a.code = code;
  a.message = error;
  g_agreed = true;
#ifdef PHASMID_WITH_MPI
  if (!g_initialised || g_size < 2) return a;
  const int first = all_min(error.empty() ? g_size : g_rank);
  if (first == g_size) return a;
  a.all_ok = false;
  a.failed_rank = first;
  if (error.empty()) a.code = 1;
  if (first != 0 && g_rank == first) {
    const std::string msg = std::to_string(code) + " " + error;
    MPI_Send(msg.data(), static_cast<int>(msg.size()), MPI_CHAR, 0, kAgreeTag, MPI_COMM_WORLD);
  } else if (first != 0 && g_rank == 0) {
    MPI_Status st;
    MPI_Probe(first, kAgreeTag, MPI_COMM_WORLD, &st);
    int n = 0;
    MPI_Get_count(&st, MPI_CHAR, &n);
    std::string msg(static_cast<std::size_t>(n), '\0');
    MPI_Recv(msg.data(), n, MPI_CHAR, first, kAgreeTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    const auto sp = msg.find(' ');
    a.code = std::atoi(msg.substr(0, sp).c_str());
    a.message = msg.substr(sp + 1);
  }
#endif
  return a;
}

int rank() { return g_rank; }
int size() { return g_size; }

}  // namespace phasmid::parallel
