#include "io/trajectory_stream.hpp"

#include "common/error.hpp"
#include "common/units.hpp"
#include "model/body_kinematics.hpp"

namespace phasmid::io {
namespace {

// The ground-contact threshold (deg) of a leg.
double threshold_deg(const model::OdeModel& m, const model::ContactLeg& l) {
  return m.parameters().at(l.threshold_param).value;
}

// Left-to-right pairs of the six-leg pattern of the three-leg model (Section 2.5.4).
const std::map<std::string, std::string>& side_numbers() {
  static const std::map<std::string, std::string> side = {{"front", "1"}, {"middle", "2"}, {"hind", "3"}};
  return side;
}

// out[k] = x(t[k] - shift) by linear interpolation over t (x's first value before t's first).
void append_delayed(AppendedDataset& time, AppendedDataset& x, double shift, bool footfall, AppendedDataset& out) {
  BlockCursor tk(time.id(), time.path()), tj(time.id(), time.path()), xj(x.id(), x.path());
  const hsize_t n = tk.size();
  const double t_front = tj.at(0), x_front = xj.at(0);
  std::vector<double> block;
  block.reserve(kStreamBlock);
  hsize_t j = 1;
  for (hsize_t k = 0; k < n; ++k) {
    const double t = tk.at(k) - shift;
    double y = x_front;
    if (t > t_front) {
      while (j < n && tj.at(j) <= t) ++j;  // the first sample after t
      if (j == n) {
        y = xj.at(n - 1);
      } else {
        const double t0 = tj.at(j - 1), t1 = tj.at(j);
        const double w = (t - t0) / (t1 - t0);
        y = (1 - w) * xj.at(j - 1) + w * xj.at(j);
      }
    }
    block.push_back(footfall ? (y < 0.5 ? 0.0 : 1.0) : y);
    if (block.size() == kStreamBlock || k + 1 == n) {
      out.append(block.data(), block.size());
      block.clear();
    }
  }
}

}  // namespace

TrajectoryStream::TrajectoryStream(H5Writer& w, const model::OdeModel& m)
    : w_(w), m_(m), time_(w, "/trajectory/time", "ms") {
  for (const auto& a : m.angles()) {
    add("/trajectory/angles/" + a.leg + "/" + a.joint, "deg", a.angle_state, Kind::Degrees);
    add("/trajectory/angular_velocity/" + a.leg + "/" + a.joint, "deg/s", a.velocity_state, Kind::Degrees);
  }
  // Footfall pattern of walking models: 1 swing, 0 stance (ground contact: beta below the
  // leg's threshold, docs/walking_model.md).
  for (const model::ContactLeg& l : m.structure().contact_legs)
    add("/trajectory/footfall/" + l.leg, "1", l.beta_state, Kind::SwingAboveRad,
        units::deg_to_rad(threshold_deg(m, l)));
  // The left side L1-L3 of the six-leg pattern is the simulated front, middle, hind leg.
  if (m.structure().contralateral) {
    for (const auto& a : m.angles()) {
      auto it = side_numbers().find(a.leg);
      if (it == side_numbers().end()) continue;
      add("/trajectory/angles/L" + it->second + "/" + a.joint, "deg", a.angle_state, Kind::Degrees);
      const model::ContactLeg* contact = m.contact_leg(a.leg);
      if (a.joint == "ctr" && contact)
        add("/trajectory/footfall/L" + it->second, "1", a.angle_state, Kind::SwingAboveDeg, threshold_deg(m, *contact));
    }
  }
  for (size_t i = 0; i < m.num_states(); ++i)
    add("/trajectory/states/" + m.states()[i].name, m.states()[i].unit, i, Kind::Raw);
  t_block_.resize(kStreamBlock);
  block_.resize(columns_.size() * kStreamBlock);
}

void TrajectoryStream::add(const std::string& path, const std::string& units, size_t state, Kind kind,
                           double threshold) {
  by_path_[path] = columns_.size();
  columns_.push_back({state, kind, threshold, std::make_unique<AppendedDataset>(w_, path, units)});
}

void TrajectoryStream::record(double t, const double* y, size_t n) {
  if (n != m_.num_states()) throw Error("internal: trajectory stream got a state of the wrong size");
  t_block_[fill_] = t;
  double* out = block_.data() + fill_;
  for (const Column& c : columns_) {
    const double v = y[c.state];
    switch (c.kind) {
      case Kind::Degrees: *out = units::rad_to_deg(v); break;
      case Kind::Raw: *out = v; break;
      case Kind::SwingAboveRad: *out = v < c.threshold ? 0.0 : 1.0; break;
      case Kind::SwingAboveDeg: *out = units::rad_to_deg(v) < c.threshold ? 0.0 : 1.0; break;
    }
    out += kStreamBlock;
  }
  if (++fill_ == kStreamBlock) flush();
}

void TrajectoryStream::flush() {
  time_.append(t_block_.data(), fill_);
  for (size_t c = 0; c < columns_.size(); ++c) columns_[c].ds->append(block_.data() + c * kStreamBlock, fill_);
  fill_ = 0;
}

AppendedDataset& TrajectoryStream::dataset(const std::string& path) {
  auto it = by_path_.find(path);
  if (it == by_path_.end()) throw Error("internal: trajectory stream has no dataset " + path);
  return *columns_[it->second].ds;
}

void TrajectoryStream::finish() {
  if (finished_) return;
  flush();
  write_right_side();
  write_body_path();
  finished_ = true;
}

// The right side R1-R3: the left side's pattern delayed by the declared lag * period.
void TrajectoryStream::write_right_side() {
  const auto& copy = m_.structure().contralateral;
  if (!copy) return;
  const double shift = m_.parameters().at(copy->lag_param).value * m_.parameters().at(copy->period_param).value;
  for (const auto& a : m_.angles()) {
    auto it = side_numbers().find(a.leg);
    if (it == side_numbers().end()) continue;
    AppendedDataset right(w_, "/trajectory/angles/R" + it->second + "/" + a.joint, "deg");
    append_delayed(time_, dataset("/trajectory/angles/L" + it->second + "/" + a.joint), shift, false, right);
    if (a.joint == "ctr" && m_.contact_leg(a.leg)) {
      AppendedDataset footfall(w_, "/trajectory/footfall/R" + it->second, "1");
      append_delayed(time_, dataset("/trajectory/footfall/L" + it->second), shift, true, footfall);
    }
  }
}

// Curve walking (Section 3.2.3): body path from the two middle legs, docs/walking_model.md.
void TrajectoryStream::write_body_path() {
  const model::ContactLeg* body_left = m_.structure().body ? m_.contact_leg(m_.structure().body->left_leg) : nullptr;
  if (!body_left) return;
  const model::BodyGeometry& body = *m_.structure().body;
  auto cursor = [&](const std::string& leg, const std::string& joint) {
    AppendedDataset& d = dataset("/trajectory/angles/" + leg + "/" + joint);
    return BlockCursor(d.id(), d.path());
  };
  BlockCursor aL = cursor(body.left_leg, "thc"), bL = cursor(body.left_leg, "ctr");
  BlockCursor aR = cursor(body.right_leg, "thc"), bR = cursor(body.right_leg, "ctr");
  AppendedDataset x(w_, "/body/x", "mm"), y(w_, "/body/y", "mm"), heading(w_, "/body/heading", "deg");
  const double thr = threshold_deg(m_, *body_left), reach = m_.parameters().at(body.reach_param).value,
               half_width = m_.parameters().at(body.half_width_param).value;
  std::vector<double> xb{0.0}, yb{0.0}, hb{0.0};  // the path starts at the origin, heading +x
  model::BodyPose pose;
  const hsize_t n = aL.size();
  for (hsize_t k = 1; k < n; ++k) {
    const double a_l[2] = {aL.at(k - 1), aL.at(k)}, b_l[2] = {bL.at(k - 1), bL.at(k)};
    const double a_r[2] = {aR.at(k - 1), aR.at(k)}, b_r[2] = {bR.at(k - 1), bR.at(k)};
    model::body_path_step(pose, a_l, b_l, a_r, b_r, thr, reach, half_width);
    xb.push_back(pose.x);
    yb.push_back(pose.y);
    hb.push_back(pose.theta / units::kRadPerDeg);
    if (xb.size() == kStreamBlock || k + 1 == n) {
      x.append(xb.data(), xb.size());
      y.append(yb.data(), yb.size());
      heading.append(hb.data(), hb.size());
      xb.clear();
      yb.clear();
      hb.clear();
    }
  }
  if (n == 1) {
    x.append(xb.data(), xb.size());
    y.append(yb.data(), yb.size());
    heading.append(hb.data(), hb.size());
  }
}

}  // namespace phasmid::io
