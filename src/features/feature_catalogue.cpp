// What compute_features can return for a model, entry by entry in its compute order
// (features.cpp for the channels, leg_features.cpp for the legs); tests/features/
// test_feature_catalogue.cpp fails if the two disagree.
#include "features/feature_parts.hpp"
#include "model/leg_tables.hpp"

namespace phasmid::features {
namespace {

void channel_catalogue(const model::OdeModel& model, std::vector<FeatureInfo>& out) {
  if (model.angles().empty()) return;
  const auto& first = model.angles().front();
  out.push_back({"period_ms", "ms", true, "cycle period of the first angle channel (" + first.leg + "." + first.joint + ")"});
  for (size_t c = 0; c < model.angles().size(); ++c) {
    const auto& ch = model.angles()[c];
    const std::string pre = ch.leg + "." + ch.joint + ".";
    const model::JointNaming nm = model::joint_naming(model::parse_joint(ch.joint));
    const std::string inc = nm.phase_inc, dec = nm.phase_dec;
    out.push_back({pre + "period_ms", "ms", true, "mean time between the angle's maxima"});
    out.push_back({pre + inc + "_fraction", "1", true, "mean " + inc + " time / period"});
    if (c > 0)
      out.push_back({pre + "phase_lag", "1", true, "mean lag of the angle's maxima after the first channel's, in its periods"});
    out.push_back({pre + inc + "_ms", "ms", true, "mean duration of " + inc + " (angle rising, minimum to maximum)"});
    out.push_back({pre + dec + "_ms", "ms", true, "mean duration of " + dec + " (angle falling, maximum to minimum)"});
    out.push_back({pre + "phase_ratio", "1", true, inc + " time / " + dec + " time"});
    out.push_back({pre + "angle_min_deg", "deg", true, "mean angle at the turning-point minima"});
    out.push_back({pre + "angle_max_deg", "deg", true, "mean angle at the turning-point maxima"});
  }
}

void leg_catalogue(const model::OdeModel& model, std::vector<FeatureInfo>& out) {
  for (const model::ContactLeg& l : model.structure().contact_legs) {
    const std::string pre = l.leg + ".";
    for (const auto& ch : model.angles())
      if (ch.leg == l.leg && ch.joint != "ctr")
        out.push_back({pre + ch.joint + ".stance_change_deg", "deg", true,
                       "mean change of the " + ch.joint + " angle from touch-down to lift-off"});
    out.push_back({pre + "step_period_ms", "ms", true, "mean time between lift-offs"});
    out.push_back({pre + "stance_ms", "ms", true, "mean stance duration (touch-down to lift-off)"});
    out.push_back({pre + "swing_ms", "ms", true, "mean swing duration (lift-off to touch-down)"});
    out.push_back({pre + "duty_factor", "1", true, "stance / (stance + swing)"});
    if (l.retractor_state) {
      out.push_back({pre + "protraction_in_stance_fraction", "1", true,
                     "fraction of the PR protraction (retractor CPG inactive) spent in stance"});
      out.push_back({pre + "stance_retraction_fraction", "1", true, "fraction of the stance with the retractor CPG active"});
    }
  }
  auto has = [&](const char* leg) { return model.contact_leg(leg) != nullptr; };
  for (auto& pr : detail::kLagPairs)
    if (has(pr[0]) && has(pr[1]))
      out.push_back({std::string("phase_lag.") + pr[0] + "_to_" + pr[1], "1", true,
                     std::string("circular mean lag of the ") + pr[1] + " leg's lift-offs after the " + pr[0] +
                         " leg's, in its step periods"});
  if (has("hind") && has("middle") && has("front"))
    out.push_back({"gait_class", "1", false, "2 tripod, 1 tetrapod, 0 irregular, from the three phase lags (a class: no gradient)"});
}

}  // namespace

std::vector<FeatureInfo> feature_catalogue(const model::OdeModel& model) {
  std::vector<FeatureInfo> out;
  channel_catalogue(model, out);
  leg_catalogue(model, out);
  if (model.angles().empty()) return out;
  out.push_back({"oscillates", "1", false, "1 when the first angle channel has a period over the window (the rhythm exists), else 0"});
  if (detail::has_three_contact_legs(model)) {
    out.push_back({"is_tripod", "1", false, "1 when gait_class is 2 (tripod), else 0 (also where the gait is undefined)"});
    out.push_back({"is_tetrapod", "1", false, "1 when gait_class is 1 (tetrapod), else 0 (also where the gait is undefined)"});
  }
  return out;
}

}  // namespace phasmid::features
