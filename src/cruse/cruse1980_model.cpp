#include "cruse/cruse1980_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/error.hpp"

namespace phasmid::cruse {
namespace {

// Comparisons of positions allow this slack so that event-exact stepping lands on thresholds.
constexpr double kSlack = 1e-9;

struct Connection {
  int controlling;
  int controlled;
  bool during_protraction;  // true: T2 cross connection; false: T1 switch
  double switch_position;   // used when !during_protraction
  // T1 switch state: armed while the controlling oscillator is short of its switch position;
  // the crossing lowers the threshold until the controlled oscillator protracts (one trigger
  // per controlling step) or the controlling one does (the switch is direction-sensitive).
  bool armed = true;
  bool latched = false;
};

class Network {
 public:
  explicit Network(const Parameters& p) : p_(p) {
    const double sl = p.switch_position("SL"), sr = p.switch_position("SR"), s1 = p.switch_position("SL1R1");
    links_ = {{L1, L2, false, sl}, {L2, L3, false, sl}, {L1, R1, false, s1}, {R1, R2, false, sr}, {R2, R3, false, sr}};
    if (p.get("coupling.contralateral") == 0) links_ = {{L1, L2, false, sl}, {L2, L3, false, sl}, {R1, R2, false, sr}, {R2, R3, false, sr}};
    else links_.insert(links_.end(), {{L1, R2, true, 0.0}, {L2, R3, true, 0.0}});
    const auto start = table2_start(p.start_position());
    for (int i = 0; i < kLegCount; ++i) {
      x_[i] = start[i];
      protracting_[i] = false;  // Table 2 gives positions only; all legs start retracting.
      t0_[i] = p.t0(i);
    }
    v_ret_ = p.get("retraction_rate");
    v_pro_ = p.protraction_rate();
    t1_ = p.get("T1");
    t2_ = p.get("T2");
  }

  bool link_active(const Connection& c) const {
    if (c.during_protraction) return protracting_[c.controlling];
    return c.latched;
  }

  // A retracting controller that has reached its switch position throws the switch once per step.
  bool update_switches() {
    bool changed = false;
    for (auto& c : links_) {
      if (c.during_protraction) continue;
      const bool beyond = !protracting_[c.controlling] && x_[c.controlling] >= c.switch_position - kSlack;
      if (beyond && c.armed) {
        c.armed = false;
        c.latched = true;
        changed = true;
      } else if (protracting_[c.controlling]) {
        c.armed = true;
        c.latched = false;
      }
    }
    return changed;
  }

  double threshold(int leg) const {
    double th = t0_[leg];
    for (const auto& c : links_)
      if (c.controlled == leg && link_active(c)) th = std::min(th, c.during_protraction ? t2_ : t1_);
    return th;
  }

  // Applies every phase change due at time t, including cascades within the same instant.
  void resolve(double t, Trajectory& out) {
    for (int pass = 0; pass < 4 * kLegCount + 4; ++pass) {
      bool changed = update_switches();
      std::array<double, kLegCount> th{};
      for (int i = 0; i < kLegCount; ++i) th[i] = threshold(i);
      for (int i = 0; i < kLegCount; ++i) {
        if (!protracting_[i] && x_[i] >= th[i] - kSlack) {
          protracting_[i] = true;
          out.onsets_ms[i].push_back(t);
          for (auto& c : links_)
            if (c.controlled == i && !c.during_protraction) c.latched = false;
          changed = true;
        } else if (protracting_[i] && x_[i] <= kSlack) {
          protracting_[i] = false;
          x_[i] = 0.0;
          changed = true;
        }
      }
      if (!changed) return;
    }
    throw SolverError("cruse1980: phase changes did not settle at t = " + std::to_string(t) + " ms");
  }

  // Linear motion over dt; protraction stops at the AEP (zero).
  void advance(double dt) {
    for (int i = 0; i < kLegCount; ++i)
      x_[i] = protracting_[i] ? std::max(0.0, x_[i] - v_pro_ * dt) : x_[i] + v_ret_ * dt;
  }

  // Time until the next threshold crossing, AEP arrival or switch turning on.
  double time_to_next_event() const {
    double dt = std::numeric_limits<double>::infinity();
    for (int i = 0; i < kLegCount; ++i) {
      if (protracting_[i]) dt = std::min(dt, x_[i] / v_pro_);
      else dt = std::min(dt, std::max(0.0, threshold(i) - x_[i]) / v_ret_);
    }
    for (const auto& c : links_)
      if (!c.during_protraction && c.armed && !protracting_[c.controlling] && x_[c.controlling] < c.switch_position - kSlack)
        dt = std::min(dt, (c.switch_position - x_[c.controlling]) / v_ret_);
    return dt;
  }

  void sample(double t, Trajectory& out) const {
    out.time_ms.push_back(t);
    for (int i = 0; i < kLegCount; ++i) {
      out.position[i].push_back(x_[i]);
      out.protraction[i].push_back(protracting_[i] ? 1.0 : 0.0);
    }
  }

 private:
  const Parameters& p_;
  std::vector<Connection> links_;
  std::array<double, kLegCount> x_{}, t0_{};
  std::array<bool, kLegCount> protracting_{};
  double v_ret_ = 0, v_pro_ = 0, t1_ = 0, t2_ = 0;
};

}  // namespace

Trajectory simulate(const Parameters& p) {
  Network net(p);
  Trajectory out;
  const double duration = p.get("duration_ms");
  if (p.stepping == Stepping::Raster) {
    // Cruse's Fortran scheme: decisions only at raster instants, linear motion in between.
    const double dt = p.get("raster_ms");
    const auto steps = static_cast<long>(std::floor(duration / dt + 1e-9));
    for (long k = 0; k <= steps; ++k) {
      const double t = k * dt;
      net.resolve(t, out);
      net.sample(t, out);
      net.advance(dt);
    }
    return out;
  }
  // Event-exact: the piecewise-linear motion is advanced from event to event, and sampled on
  // the output grid.
  const double out_dt = p.get("output_step_ms");
  const auto samples = static_cast<long>(std::floor(duration / out_dt + 1e-9));
  double t = 0.0;
  long next_sample = 0;
  net.resolve(t, out);
  while (next_sample <= samples) {
    const double t_sample = next_sample * out_dt;
    const double dt_event = net.time_to_next_event();
    if (t + dt_event < t_sample - 1e-12) {
      net.advance(dt_event);
      t += dt_event;
    } else {
      net.advance(t_sample - t);
      t = t_sample;
      ++next_sample;
      net.resolve(t, out);
      net.sample(t, out);
      continue;
    }
    net.resolve(t, out);
  }
  return out;
}

}  // namespace phasmid::cruse
