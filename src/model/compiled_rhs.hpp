#pragma once
// Right-hand sides compiled for one model: a model writes the C++ of its evaluation with every
// index a literal (NetworkModel::rhs_source), this compiles it with the compiler and flags
// phasmid was built with into a shared object, loads it and returns the function, as Brian2's
// standalone device does for its equations. Floating-point semantics are those of the build
// (no fast-math; -ffp-contract=off with -march=native), so a compiled evaluation returns the
// generic one's values bit for bit (tests/model/test_compiled_rhs.cpp).
//
// Contract:
//  - Objects are cached by a hash of compiler, flags, phasmid's version, the headers the source
//    includes (so an edit of the equations compiles anew) and the source itself: in
//    $PHASMID_CACHE_DIR, else $XDG_CACHE_HOME/phasmid, else $HOME/.cache/phasmid. A cached
//    object is loaded without compiling; within a process each source is compiled and loaded
//    once (sweeps' threads share it). Objects are written under a temporary name and renamed,
//    so concurrent processes never load a half-written one.
//  - compile_rhs never throws for a failed compilation: it returns nullptr and the reason
//    (naming the compiler's log) in *why; callers fall back to the generic evaluation.
//  - Loaded objects stay loaded until the process ends.
#include <string>

#include "model/compiled_rhs_abi.hpp"

namespace phasmid::model {

// The lines every generated source starts with (includes and the ABI).
std::string compiled_rhs_preamble();

// The function `symbol` of `source`, compiled and loaded (or from the caches); nullptr and the
// reason in *why if compilation or loading failed.
PhasmidRhsFn compile_rhs(const std::string& source, const std::string& symbol, std::string* why);

// Where compiled objects are cached (the contract's order).
std::string compiled_rhs_cache_dir();

// The compile command without input and output: compiler and flags.
std::string compiled_rhs_command();

}  // namespace phasmid::model
