#pragma once
// Which SUNDIALS this process runs on: the version the library reports and the shared object
// the dynamic loader took CVODES from. scripts/setup.sh builds Debian's own SUNDIALS source
// with optimisation into build/sundials/install, because Debian's binary package is -O0 code;
// a build against the binary package loads it from /usr/lib instead: the same numbers, slower
// (docs/performance.md "What the build contributes").
#include <string>

namespace phasmid::solver {

struct SundialsLibrary {
  std::string version;  // as SUNDIALSGetVersion reports it, e.g. "6.4.1"
  std::string path;     // the file CVODES was loaded from; empty when the loader does not say
};

SundialsLibrary sundials_library();
// "SUNDIALS 6.4.1 from <path>", for `phasmid --version`.
std::string sundials_description();

}  // namespace phasmid::solver
