#pragma once
// The seam between a model and the fitting machinery (optimisers, multistart, uncertainty,
// profiles, HDF5 layout, summary): a set of estimated parameters on their scales within
// bounds, and weighted residuals r(x) with cost = 1/2 sum r^2. FitProblem (ODE models, exact
// Jacobians from forward sensitivities) and cruse::CruseFitProblem (the piecewise-linear
// Cruse (1980) oscillators, residuals only) implement it.
#include <string>
#include <vector>

#include "fit/parameter_table.hpp"

namespace phasmid::io {
class H5Writer;
}

namespace phasmid::fit {

class ResidualProblem {
 public:
  virtual ~ResidualProblem() = default;

  size_t num_parameters() const { return est_.size(); }  // estimated
  size_t num_residuals() const { return labels_.size(); }
  const std::vector<std::string>& residual_labels() const { return labels_; }
  const std::vector<FitParameter>& estimated() const { return est_; }
  const std::vector<FitParameter>& all_parameters() const { return params_; }
  std::vector<std::string> parameter_names() const;

  // Scaled start (nominal values) and bounds; linear-scale values of the estimated parameters.
  std::vector<double> start() const;
  std::vector<double> lower() const;
  std::vector<double> upper() const;
  std::vector<double> to_linear(const std::vector<double>& x) const;

  virtual std::string parameter_unit(size_t j) const = 0;                // of estimated parameter j
  virtual std::vector<std::string> tied_parameters(size_t j) const = 0;  // model parameters it sets

  // False: evaluate() cannot return a Jacobian (J must be nullptr); only derivative-free
  // optimisers apply and there are no standard errors or profiles.
  virtual bool has_jacobian() const { return true; }
  // Why there is no Jacobian (one sentence), for error messages.
  virtual std::string no_jacobian_reason() const { return ""; }

  // Residuals r (num_residuals) and, if J != nullptr, dr/dx (row-major m x n). Returns false
  // (with the reason in *error) if the model run fails or a target cannot be computed.
  virtual bool evaluate(const double* x, double* r, double* J, std::string* error = nullptr) const = 0;

  // The model at scaled estimates x (the best fit) under the fit's HDF5 group: /trajectory,
  // /parameters, /features as the model's own run verb writes them. `usable` false: only the
  // parameter vector at x (the start). Throws Error if the model run fails.
  virtual void write_model_output(io::H5Writer& out, const double* x, bool usable, double output_dt_ms) const = 0;

 protected:
  std::vector<FitParameter> params_, est_;
  std::vector<std::string> labels_;
};

}  // namespace phasmid::fit
