#pragma once
// The one-line error that building a model from config `text` (origin "bad.toml") raises, or
// "no error": shared by the config-error tests of triggers and stance conditions.
#include <string>

#include "common/error.hpp"
#include "config/config.hpp"

namespace phasmid::test {

inline std::string model_config_error(const std::string& text) {
  try {
    config::build_model(config::parse_config(text, "bad.toml"));
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace phasmid::test
