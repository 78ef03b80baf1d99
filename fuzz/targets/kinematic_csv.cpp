// Fuzz target: the kinematic recording readers of `phasmid fit` (fit/kinematic_data.hpp).
// The first byte chooses the format: even the phasmid CSV, odd the Anipose angle CSV with the
// options of configs/fit_fti_anipose_synthetic.toml; the rest is the file's text.
#include "common/error.hpp"
#include "fit/kinematic_data.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text = phasmid::fuzz::as_text(data + 1, size - 1);
  try {
    if (data[0] % 2 == 0) {
      phasmid::fit::parse_kinematic_csv(text, "fuzz.csv");
    } else {
      phasmid::fit::AniposeOptions o;
      o.frame_rate_hz = 200.0;
      o.columns = {{"R2_FTi_flex", "middle.fti"}, {"L1_CTr_flex", "front.ctr"}};
      phasmid::fit::parse_anipose_csv(text, "fuzz.csv", o);
    }
  } catch (const phasmid::Error&) {
  }
  return 0;
}
