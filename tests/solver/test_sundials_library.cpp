// The SUNDIALS the tests run on is the one the build linked (scripts/setup.sh: Debian's source
// built with optimisation into build/sundials/install, found through the binaries' run path),
// not another copy the loader finds first, such as Debian's -O0 binary package.
#include <gtest/gtest.h>
#include <sundials/sundials_config.h>

#include <filesystem>

#include "solver/sundials_library.hpp"

namespace fs = std::filesystem;
using phasmid::solver::sundials_library;

TEST(SundialsLibrary, TheLoadedCvodesIsTheLinkedOne) {
  const auto lib = sundials_library();
  ASSERT_FALSE(lib.path.empty());
  EXPECT_EQ(fs::canonical(lib.path), fs::canonical(PHASMID_LINKED_CVODES));
}

TEST(SundialsLibrary, VersionMatchesTheHeaders) {
  EXPECT_EQ(sundials_library().version, SUNDIALS_VERSION);
  EXPECT_NE(phasmid::solver::sundials_description().find("SUNDIALS " SUNDIALS_VERSION " from /"), std::string::npos);
}
