// Fuzz target: the parameter table (TSV) of `phasmid fit --parameters` (fit/parameter_table.hpp),
// each row validated and written back.
#include "common/error.hpp"
#include "fit/parameter_table.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    auto params = phasmid::fit::parse_parameter_table(phasmid::fuzz::as_text(data, size), "fuzz.tsv");
    for (const auto& p : params) phasmid::fit::validate(p);
    phasmid::fit::format_parameter_table(params);
  } catch (const phasmid::Error&) {
  }
  return 0;
}
