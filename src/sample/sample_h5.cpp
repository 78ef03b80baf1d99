// /sample of `phasmid sample` (docs/hdf5.md, "/sample").
#include <cmath>

#include "io/h5_file.hpp"
#include "sample/sample_run.hpp"

namespace phasmid::sample {

namespace {

void write_draws(io::H5Writer& out, const fit::ResidualProblem& problem, const SampleResult& res) {
  const SamplerResult& r = res.run;
  std::vector<double> lin(r.x.size());
  for (std::size_t k = 0; k < r.x.size(); ++k) lin[k] = fit::from_scaled(problem.estimated()[k % r.dim].scale, r.x[k]);
  out.write("/sample/draws", lin, "parameter units (/sample/parameter_units), chain x draw x parameter",
            {r.chains, r.draws, r.dim});
  std::vector<double> lpost(r.log_prior.size());
  for (std::size_t k = 0; k < lpost.size(); ++k) lpost[k] = r.log_prior[k] + r.log_likelihood[k];
  out.write("/sample/log_posterior", lpost, "1 (natural log, up to a constant), chain x draw", {r.chains, r.draws});
  out.write("/sample/log_likelihood", r.log_likelihood, "1 (natural log, -1/2 sum r^2), chain x draw", {r.chains, r.draws});
  out.write("/sample/log_prior", r.log_prior, "1 (natural log, density of the scaled parameters)", {r.chains, r.draws});
}

void write_parameters(io::H5Writer& out, const fit::ResidualProblem& problem) {
  std::vector<std::string> units, scales, priors;
  for (std::size_t j = 0; j < problem.num_parameters(); ++j) {
    const auto& p = problem.estimated()[j];
    units.push_back(problem.parameter_unit(j));
    scales.push_back(fit::scale_name(p.scale));
    priors.push_back(p.prior.declared ? std::string(fit::prior_name(p.prior.type)) + "(" + fit::format_prior_parameters(p.prior) + ")"
                                      : "parameterScaleUniform(bounds)");
  }
  out.write("/sample/parameter_names", problem.parameter_names());
  out.write("/sample/parameter_units", units);
  out.write("/sample/parameter_scales", scales);
  out.write("/sample/priors", priors);
}

void write_diagnostics(io::H5Writer& out, const SampleResult& res) {
  const SamplerResult& r = res.run;
  std::vector<double> ess, rhat, mean, sd, median, q025, q975;
  for (const auto& s : res.parameters) {
    ess.push_back(s.ess), rhat.push_back(s.rhat), mean.push_back(s.mean), sd.push_back(s.sd);
    median.push_back(s.median), q025.push_back(s.q025), q975.push_back(s.q975);
  }
  out.write("/sample/diagnostics/ess", ess, "draws (after burn-in, all chains)");
  out.write("/sample/diagnostics/split_rhat", rhat, "1");
  out.write_scalar("/sample/diagnostics/burn_in", static_cast<double>(res.burn_in), "draws");
  out.write("/sample/diagnostics/acceptance", r.acceptance, "1 (per chain, beta = 1)");
  out.write("/sample/diagnostics/warnings", res.warnings.empty() ? std::vector<std::string>{""} : res.warnings);
  out.write("/sample/summary/mean", mean, "parameter units");
  out.write("/sample/summary/sd", sd, "parameter units");
  out.write("/sample/summary/median", median, "parameter units");
  out.write("/sample/summary/q025", q025, "parameter units");
  out.write("/sample/summary/q975", q975, "parameter units");
  if (r.temperatures > 1) {
    out.write("/sample/tempering/betas", r.betas, "1 (final ladder, chain x temperature)", {r.chains, r.temperatures});
    out.write("/sample/tempering/swap_acceptance", r.swap_acceptance, "1 (chain x neighbouring pair, coldest first)",
              {r.chains, r.temperatures - 1});
  }
}

void write_evidence(io::H5Writer& out, const Evidence& e) {
  if (!e.ok) return;
  out.write_scalar("/sample/evidence/log_evidence", e.log_evidence, "1 (natural log, up to the fixed noises' constant)");
  out.write_scalar("/sample/evidence/error", e.error(), "1");
  out.write_scalar("/sample/evidence/mc_error", e.mc_error, "1");
  out.write_scalar("/sample/evidence/discretisation_error", e.discretisation_error, "1");
  out.write("/sample/evidence/betas", e.betas, "1 (chain 0's fixed ladder, coldest first)");
  out.write("/sample/evidence/mean_log_likelihood", e.mean_log_likelihood, "1 (per level, mean over chains)");
}

void write_settings(io::H5Writer& out, const SampleSpec& spec, const SampleResult& res) {
  const SamplerOptions& o = spec.sampler;
  out.set_attribute("/sample", "sampler", o.temperatures > 1 ? std::string("parallel_tempering") : std::string("adaptive_metropolis"));
  out.set_attribute("/sample", "chains", static_cast<double>(o.chains));
  out.set_attribute("/sample", "draws", static_cast<double>(o.draws));
  out.set_attribute("/sample", "temperatures", static_cast<double>(o.temperatures));
  out.set_attribute("/sample", "max_temperature", o.max_temperature);
  out.set_attribute("/sample", "prior_level", o.prior_level ? 1.0 : 0.0);
  out.set_attribute("/sample", "ladder_fixed_from", static_cast<double>(res.run.ladder_fixed_from));
  out.set_attribute("/sample", "seed", static_cast<double>(o.seed));
  out.set_attribute("/sample", "start", std::string(start_name(spec.start)));
  out.set_attribute("/sample", "target_acceptance", o.proposal.target_acceptance);
  out.set_attribute("/sample", "failed_evaluations", static_cast<double>(res.run.failed_evaluations));
}
}  // namespace

void write_sample_h5(io::H5Writer& out, const fit::ResidualProblem& problem, const SampleSpec& spec, const SampleResult& res) {
  out.ensure_group("/sample");
  write_draws(out, problem, res);
  write_parameters(out, problem);
  write_diagnostics(out, res);
  write_settings(out, spec, res);
  write_evidence(out, res.evidence);
  out.write_string("/sample/summary/text", format_result(problem, spec, res));
}

}  // namespace phasmid::sample
