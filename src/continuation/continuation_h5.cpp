#include "continuation/continuation_h5.hpp"

#include <cstdint>
#include <sstream>

#include "io/h5_file.hpp"

namespace phasmid::continuation {

namespace {

template <class F>
std::vector<double> column(const Branch& b, F f) {
  std::vector<double> v;
  for (const auto& p : b.points) v.push_back(f(p));
  return v;
}

void write_multipliers(io::H5Writer& out, const std::string& g, const Branch& b, size_t ns) {
  std::vector<double> re, im, ab;
  for (const auto& p : b.points)
    for (const auto& m : p.multipliers) re.push_back(m.real()), im.push_back(m.imag()), ab.push_back(std::abs(m));
  const std::vector<hsize_t> dims{b.points.size(), ns};
  out.write(g + "/multipliers_real", re, "1", dims);
  out.write(g + "/multipliers_imag", im, "1", dims);
  out.write(g + "/multipliers_abs", ab, "1", dims);
  std::vector<std::int64_t> trivial;
  for (const auto& p : b.points) trivial.push_back(static_cast<std::int64_t>(p.trivial));
  out.write(g + "/trivial_multiplier", trivial, "column index");
  std::vector<std::int64_t> neutral;
  for (const auto& p : b.points) neutral.push_back(static_cast<std::int64_t>(p.neutral.size()));
  out.write(g + "/neutral_multipliers", neutral, "count");
}

void write_special(io::H5Writer& out, const std::string& g, const Branch& b) {
  std::vector<std::int64_t> index;
  std::vector<std::string> kind, note;
  std::vector<double> par, period;
  for (const auto& s : b.special) {
    index.push_back(static_cast<std::int64_t>(s.index));
    kind.push_back(s.kind);
    note.push_back(s.note);
    par.push_back(s.parameter);
    period.push_back(s.period_ms);
  }
  const std::string sp = g + "/special_points";
  out.ensure_group(sp);
  out.write(sp + "/index", index, "branch point");
  out.write(sp + "/kind", kind);
  out.write(sp + "/note", note);
  out.write(sp + "/parameter", par, b.parameter_unit);
  out.write(sp + "/period_ms", period, "ms");
}

// The held phases' fractions of the period, their events' names (comma-separated) as an attribute.
void write_held_phases(io::H5Writer& out, const std::string& g, const Branch& b) {
  if (b.held_phases.empty()) return;
  std::vector<double> fractions;
  std::string names;
  for (const auto& h : b.held_phases) fractions.push_back(h.fraction), names += (names.empty() ? "" : ",") + h.name;
  out.write(g + "/held_phase_fractions", fractions, "1 (fraction of the period after the section)");
  out.set_attribute(g + "/held_phase_fractions", "names", names);
}

}  // namespace

void write_branch_h5(io::H5Writer& out, const model::OdeModel& model, const Branch& b) {
  const std::string g = "/continuation";
  const size_t ns = model.num_states();
  out.ensure_group(g);
  out.set_attribute(g, "parameter", b.parameter);
  out.set_attribute(g, "parameter_unit", b.parameter_unit);
  out.set_attribute(g, "end", b.special.empty() ? std::string() : b.special.back().kind);
  out.set_attribute(g, "shots", static_cast<double>(b.shots));
  out.set_attribute(g, "plain_shots", static_cast<double>(b.plain_shots));
  out.set_attribute(g, "seconds", b.seconds);
  out.set_attribute(g, "start", b.start_note);
  out.set_attribute(g, "section", model.states().at(b.section.state).name +
                                      (b.section.direction < 0 ? " falling through " : " rising through ") +
                                      std::to_string(b.section.level));
  out.write(g + "/parameter", column(b, [](const BranchPoint& p) { return p.parameter; }), b.parameter_unit);
  out.set_attribute(g + "/parameter", "name", b.parameter);
  out.write(g + "/period_ms", column(b, [](const BranchPoint& p) { return p.period_ms; }), "ms");
  out.write(g + "/amplitude", column(b, [](const BranchPoint& p) { return p.amplitude; }), "state units (root-sum-square of ranges)");
  out.write(g + "/residual", column(b, [](const BranchPoint& p) { return p.residual; }), "state units");
  std::vector<std::int64_t> stable, iterations;
  for (const auto& p : b.points) stable.push_back(p.stable ? 1 : 0), iterations.push_back(p.newton_iterations);
  out.write(g + "/stable", stable, "1 = stable");
  out.write(g + "/newton_iterations", iterations, "1");
  write_multipliers(out, g, b, ns);
  write_held_phases(out, g, b);
  std::vector<std::string> names;
  std::vector<double> y0;
  for (const auto& s : model.states()) names.push_back(s.name);
  for (const auto& p : b.points) y0.insert(y0.end(), p.y0.begin(), p.y0.end());
  out.write(g + "/state_names", names);
  out.write(g + "/state_on_section", y0, "state units (see state_names)", {b.points.size(), ns});
  out.ensure_group(g + "/features");
  for (size_t j = 0; j < b.feature_names.size(); ++j)
    out.write(g + "/features/" + b.feature_names[j], column(b, [j](const BranchPoint& p) { return p.features[j]; }),
              b.feature_units[j]);
  write_special(out, g, b);
}

std::string format_summary(const Branch& b) {
  std::ostringstream s;
  s << b.points.size() << " cycles along " << b.parameter;
  if (!b.points.empty())
    s << " from " << b.points.front().parameter << " (period " << b.points.front().period_ms << " ms) to "
      << b.points.back().parameter << " (period " << b.points.back().period_ms << " ms)";
  s << "; " << b.shots << " integrations with the monodromy and " << b.plain_shots << " without in " << b.seconds
    << " s\n";
  if (!b.start_note.empty()) s << "  " << b.start_note << "\n";
  for (const auto& h : b.held_phases) s << "  held phase: " << h.name << " at " << h.fraction << " of the period\n";
  for (const auto& sp : b.special)
    s << "  " << sp.kind << " at " << b.parameter << " = " << sp.parameter << " " << b.parameter_unit << ", period "
      << sp.period_ms << " ms (point " << sp.index << (sp.note.empty() ? "" : "; " + sp.note) << ")\n";
  return s.str();
}

}  // namespace phasmid::continuation
