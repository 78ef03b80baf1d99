#include "solver/sundials_library.hpp"

#include <cvodes/cvodes.h>
#include <dlfcn.h>
#include <sundials/sundials_version.h>

namespace phasmid::solver {

SundialsLibrary sundials_library() {
  SundialsLibrary lib;
  char version[64] = {};
  if (SUNDIALSGetVersion(version, sizeof version) == 0) lib.version = version;
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&CVodeCreate), &info) != 0 && info.dli_fname) lib.path = info.dli_fname;
  return lib;
}

std::string sundials_description() {
  const SundialsLibrary lib = sundials_library();
  return "SUNDIALS " + (lib.version.empty() ? std::string("(version unknown)") : lib.version) +
         (lib.path.empty() ? "" : " from " + lib.path);
}

}  // namespace phasmid::solver
