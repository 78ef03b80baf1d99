#pragma once
// A model assembled into one flat ODE system (AMICI's "Model"): named states, one vector of
// named parameters, a right-hand side written once as a template and instantiated for
// double (simulation), Jet<1> (directional derivatives: sensitivity right-hand sides) and
// Jet<4> / Jet<kJacobianChunk> (several directions at once: Jacobian columns and sensitivity
// right-hand sides in chunks; Jet<4> for the last chunk when it has at most four, so that a
// run with two to four parameters does not pay for eight lanes). Time is in ms throughout.
#include <ceres/jet.h>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "model/command_trigger.hpp"
#include "model/parameters.hpp"

namespace phasmid::model {

constexpr int kJacobianChunk = 8;
using Jet1 = ceres::Jet<double, 1>;
using JetK = ceres::Jet<double, kJacobianChunk>;
using Jet4 = ceres::Jet<double, 4>;

// Partitioned integration (solver/partitioned_simulator.hpp): the states split into parts
// that read each other only through states they interpolate (joint angles; with the Neurons
// grain also the potentials of presynaptic neurons), so that each part can be integrated on
// its own step size.
// Joints: one part per joint network. Neurons: also the spiking cells, whose steps are short,
// apart from the network that drives them, whose equations are stiff but smooth.
enum class PartitionGrain { Joints, Neurons };

struct ModelPartition {
  std::vector<std::vector<size_t>> states;  // per part: its states (global indices, ascending)
  std::vector<std::vector<size_t>> inputs;  // per part: states of other parts its equations read
  std::vector<std::string> names;           // per part: a label for messages ("middle.fti")
  // Per part (or empty: none): stiff and smooth, without spikes. A run with an explicit
  // integrator integrates these parts with CVODES BDF (SolverOptions::stiff_part_tol).
  std::vector<char> stiff;
  size_t size() const { return states.size(); }
  bool is_stiff(size_t k) const { return k < stiff.size() && stiff[k]; }
};

// The equations of one part: reads a full-size state vector (only the part's own states and
// its inputs need to be valid) and writes ydot only at the part's own states.
class OdeModelPart {
 public:
  virtual ~OdeModelPart() = default;
  // The parameter vector the driver's double rhs calls pass from now on: a part may keep
  // values taken from it and use them while a call passes this same pointer. The driver binds
  // again whenever it changes the vector's values (a triggered command time).
  virtual void bind(const double* p) { (void)p; }
  virtual void rhs(double t, const double* y, const double* p, double* ydot) const = 0;
  virtual void rhs(double t, const JetK* y, const JetK* p, JetK* ydot) const = 0;
  // From now on the double rhs runs code compiled for this part alone (model/compiled_rhs.hpp,
  // SolverOptions::compiled_rhs), returning the same values. False, with the reason in *why,
  // where the model kind has no such code or it could not be compiled: the part stays as it was.
  virtual bool compile(std::string* why) {
    if (why) *why = "this model kind has no compiled right-hand side";
    return false;
  }
  // Whether rhs_packed is available (a part of a partition, compiled): the driver then hands
  // the part its own states and inputs as they are, without spreading them into full vectors.
  virtual bool packed() const { return false; }
  // The double rhs on packed vectors: y the part's own states in ModelPartition::states[k]'s
  // order, u its inputs in ModelPartition::inputs[k]'s order; ydot[i] is what rhs writes at
  // the full index of y[i]. Only where packed() is true.
  virtual void rhs_packed(double t, const double* y, const double* u, const double* p, double* ydot) const {
    (void)t, (void)y, (void)u, (void)p, (void)ydot;
  }
};

// Where packed vectors keep their entries: own[i] is the full index of y[i] and ydot[i],
// inputs[j] that of u[j]. No own states: the vectors are the full ones (a whole model).
struct RhsLayout {
  std::vector<size_t> own, inputs;
};

struct StateInfo {
  std::string name;  // e.g. "middle.fti.gamma", "middle.fti.cpg_ext.V"
  std::string unit;  // unit of the state as integrated (rad, rad/ms, mV, 1, mN/mm^2)
};

// A joint angle of the model, for output in degrees and for gait features.
struct AngleChannel {
  std::string leg;    // front | middle | hind (or L1..R3)
  std::string joint;  // thc | ctr | fti
  size_t angle_state;     // index of the angle state (rad)
  size_t velocity_state;  // index of its angular velocity (rad/ms)
};

// ---- what the model has, declared by its builder (docs/walking_model.md) --------------------
// Generic layers (features, triggers, trajectory writer, fit) learn a model's structure from
// this declaration only, never from parameter names.

// A leg with ground contact: stance while its CTr angle beta is below the threshold; the
// touch-down and lift-off events, footfall patterns and per-leg gait features follow from it.
struct ContactLeg {
  std::string leg;               // front | middle | hind (or L2, R2)
  size_t beta_state;             // CTr angle (rad)
  size_t threshold_param;        // ground-contact threshold on beta (deg)
  // The PR system's retractor CPG neuron (V, mV), counted active above the parameter
  // retractor_level_param (mV); none if the leg has no PR network.
  std::optional<size_t> retractor_state;
  size_t retractor_level_param = 0;
};

// A neuron of a network model: its name and membrane potential state (mV).
struct NeuronInfo {
  std::string name;  // "middle.fti.cpg_flx"
  size_t v_state;
};

// The six-leg output of a three-leg model: the right side is the simulated left side delayed
// by lag * period (parameters, 1 and ms).
struct ContralateralCopy {
  size_t lag_param;
  size_t period_param;
};

// Curve walking: the two legs (each a ContactLeg with thc and ctr channels) that move the
// kinematic body (model/body_kinematics.hpp) and its geometry parameters (mm).
struct BodyGeometry {
  std::string left_leg, right_leg;
  size_t reach_param;
  size_t half_width_param;
};

struct ModelStructure {
  std::vector<ContactLeg> contact_legs;  // in the order of their CTr angle channels
  std::vector<NeuronInfo> neurons;
  std::optional<ContralateralCopy> contralateral;
  std::optional<BodyGeometry> body;
};

class OdeModel {
 public:
  virtual ~OdeModel() = default;
  virtual std::string kind() const = 0;

  size_t num_states() const { return states_.size(); }
  const std::vector<StateInfo>& states() const { return states_; }
  size_t state_index(const std::string& name) const;
  ParameterSet& parameters() { return params_; }
  const ParameterSet& parameters() const { return params_; }
  const std::vector<AngleChannel>& angles() const { return angles_; }
  const ModelStructure& structure() const { return structure_; }
  // The contact leg named `leg`, or nullptr.
  const ContactLeg* contact_leg(const std::string& leg) const;

  virtual std::vector<double> initial_state(const std::vector<double>& p) const = 0;
  virtual void rhs(double t, const double* y, const double* p, double* ydot) const = 0;
  virtual void rhs(double t, const Jet1* y, const Jet1* p, Jet1* ydot) const = 0;
  virtual void rhs(double t, const Jet4* y, const Jet4* p, Jet4* ydot) const = 0;
  virtual void rhs(double t, const JetK* y, const JetK* p, JetK* ydot) const = 0;

  // Times (ms) at which the right-hand side changes discontinuously by a central command;
  // the solver stops and restarts there instead of stepping across.
  virtual std::vector<double> breakpoints(const std::vector<double>& p, double t_end) const {
    (void)p; (void)t_end;
    return {};
  }

  // Command times resolved from events during the run (empty: all command times fixed).
  const std::vector<CommandTrigger>& triggers() const { return triggers_; }
  void set_triggers(std::vector<CommandTrigger> t) { triggers_ = std::move(t); }

  // Bandwidth (lower, upper) of the Jacobian when states are ordered as declared; -1 if dense.
  virtual int jacobian_half_bandwidth() const { return -1; }

  // The model's parts for partitioned integration at a grain (empty: the model cannot be
  // partitioned; a model without a finer split gives its Joints partition for Neurons) and the
  // equations of part k of that partition.
  virtual ModelPartition partition(PartitionGrain grain) const {
    (void)grain;
    return {};
  }
  virtual std::unique_ptr<OdeModelPart> make_part(const ModelPartition& partition, size_t k) const {
    (void)partition; (void)k;
    return nullptr;
  }
  // The whole right-hand side as one part, for a run to bind to its parameters
  // (OdeModelPart::bind); nullptr: the run calls rhs.
  virtual std::unique_ptr<OdeModelPart> make_whole() const { return nullptr; }

 protected:
  size_t add_state(std::string name, std::string unit);
  std::vector<StateInfo> states_;
  std::vector<AngleChannel> angles_;
  ModelStructure structure_;
  ParameterSet params_;
  std::vector<CommandTrigger> triggers_;
};

// CRTP bridge: Derived implements one `template <class T> void eval(double t, const T* y,
// const T* p, T* ydot) const`, and gets the four virtual instantiations.
template <class Derived>
class OdeModelT : public OdeModel {
 public:
  void rhs(double t, const double* y, const double* p, double* ydot) const override {
    static_cast<const Derived*>(this)->eval(t, y, p, ydot);
  }
  void rhs(double t, const Jet1* y, const Jet1* p, Jet1* ydot) const override {
    static_cast<const Derived*>(this)->eval(t, y, p, ydot);
  }
  void rhs(double t, const Jet4* y, const Jet4* p, Jet4* ydot) const override {
    static_cast<const Derived*>(this)->eval(t, y, p, ydot);
  }
  void rhs(double t, const JetK* y, const JetK* p, JetK* ydot) const override {
    static_cast<const Derived*>(this)->eval(t, y, p, ydot);
  }
};

// Scalar value of a double or Jet (for branching on state values inside templates).
inline double value_of(double x) { return x; }
template <int N>
double value_of(const ceres::Jet<double, N>& x) { return x.a; }

}  // namespace phasmid::model
