#pragma once
// Each CLI verb lives in its own src/app/verb_<name>.cpp and registers itself here, so that
// adding a verb never touches main.cpp.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "output/run_file.hpp"

namespace phasmid::app {

struct Verb {
  std::string name;
  std::string description;
  // Adds options to `sub` and returns the action to run when the verb is chosen.
  std::function<std::function<int()>(CLI::App& sub)> setup;
};

std::vector<Verb>& verbs();

struct RegisterVerb {
  explicit RegisterVerb(Verb v) { verbs().push_back(std::move(v)); }
};

// The full command line as typed, for the HDF5 `command` attribute (main sets it).
using output::command_line;

}  // namespace phasmid::app
