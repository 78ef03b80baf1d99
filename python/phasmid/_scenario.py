"""Scenarios and the analyses run on them (docs/python.md)."""
import os
import tempfile

from . import _core
from ._results import (Parameter, Parameters, SimulationResult, SensitivityResult, FitResult,
                       SweepResult)


def _sets(values):
    """{name: value} or ["name=value", ...] as the --set assignments of the CLI (repr keeps
    every bit of a float)."""
    if values is None:
        return []
    if isinstance(values, dict):
        return ["%s=%r" % (k, float(v)) for k, v in values.items()]
    return [str(v) for v in values]


class Scenario:
    """A scenario config made into a model: its kind, its parameters, and runs of it.

    Immutable: with_parameters() returns a new scenario. Every run releases the GIL, so
    scenarios run in parallel from threads (concurrent.futures.ThreadPoolExecutor)."""

    def __init__(self, core):
        self._core = core

    @property
    def kind(self):
        """The model kind ([model] type), e.g. "single_joint"."""
        return self._core.kind

    @property
    def path(self):
        """The config's path as given (or "embedded:configs/x.toml", or the loads() origin)."""
        return self._core.path

    @property
    def config_text(self):
        """The resolved config: the config text plus the parameter overrides."""
        return self._core.config_text

    @property
    def parameters(self):
        """Every parameter (name, value, unit, source, description, lower, upper) as Parameters."""
        return Parameters(Parameter(*r) for r in self._core.parameter_records())

    @property
    def feature_catalogue(self):
        """Every feature a run can report: (name, unit, differentiable, description) tuples."""
        return self._core.feature_catalogue()

    def with_parameters(self, values=None, **kv):
        """A new scenario with parameter values changed (a dict and/or keywords; names with dots
        need the dict). Applied like the CLI's --set, after [parameters]; self is unchanged."""
        values = dict(values or {}, **kv)
        return Scenario(self._core.with_sets(_sets(values)))

    def simulate(self, t_end_ms=None, **options):
        """Run the scenario as `phasmid simulate` does and return a SimulationResult.

        Options override [simulation]: t_end_ms, output_dt_ms, discard_ms, rtol, atol,
        max_step_ms, max_steps (solver steps per output interval). Raises SolverError when
        the integration fails."""
        if t_end_ms is not None:
            options["t_end_ms"] = t_end_ms
        return SimulationResult(self._core.simulate({k: float(v) for k, v in options.items()}), attrs=self._attrs())

    def sensitivity(self, parameters=None, method=None, t_end_ms=None, output_dt_ms=None,
                    discard_ms=None, trajectory=None):
        """Forward sensitivities as `phasmid sensitivity` computes them: the config's
        [sensitivity] section (or the [simulation] run without one), overridden by the
        arguments (parameters: names; method: "forward" or "fd"; trajectory: keep the
        times x states x parameters sensitivities). Returns a SensitivityResult."""
        return SensitivityResult(_core.sensitivity(
            self._core, None if parameters is None else list(parameters), method, t_end_ms,
            output_dt_ms, discard_ms, trajectory), attrs=self._attrs())

    def _attrs(self):
        return {"/": {"model": self.kind, "config": self.config_text}}

    def __repr__(self):
        return "<phasmid.Scenario %s (%s), %d parameters>" % (
            self.path, self.kind, len(self._core.parameter_records()))


def load(path, set=None):
    """Load a scenario config (a file, or the name of a shipped config such as
    "configs/single_joint_fti.toml"); `set` gives parameter overrides ({name: value} or
    ["name=value"]), applied like --set. Raises ConfigError naming file:line."""
    return Scenario(_core.Scenario.load(os.fspath(path), _sets(set)))


def loads(text, set=None, origin="<string>"):
    """A scenario from TOML text; errors name `origin`:line. See load()."""
    return Scenario(_core.Scenario.loads(text, origin, _sets(set)))


def _scenario_of(config, set):
    if isinstance(config, Scenario):
        return config._core.with_sets(_sets(set)) if set else config._core
    return _core.Scenario.load(os.fspath(config), _sets(set))


def fit(config, set=None, profile=(), **options):
    """Run the fit of a config's [fit] section as `phasmid fit` does and return a FitResult
    carrying what the HDF5 file holds. `config` is a path or a Scenario; options are the
    CLI's: data, data_format, parameters, optimizer, multistart, seed, target_set,
    max_iterations, threads; `profile` lists parameters to profile."""
    core = _scenario_of(config, set)
    with tempfile.TemporaryDirectory(prefix="phasmid-") as d:
        out = os.path.join(d, "fit.h5")
        outcome = _core.fit(core, options, list(profile), out)
        return FitResult(out, outcome)


def sweep(config, set=None, threads=0):
    """Run every point of a config's [sweep] section as `phasmid sweep` does (threads: 0 for
    OpenMP's default) and return a SweepResult. Ctrl-C finishes the running points and raises
    KeyboardInterrupt."""
    core = _scenario_of(config, set)
    with tempfile.TemporaryDirectory(prefix="phasmid-") as d:
        out = os.path.join(d, "sweep.h5")
        outcome = _core.sweep(core, int(threads), False, out)
        return SweepResult(out, outcome)


def gsa(config, **options):
    """Global sensitivity analysis: not available yet. The `phasmid gsa` verb has not reached
    this build (docs/gsa.md); phasmid.read() already loads /gsa files into a GsaResult."""
    raise NotImplementedError("phasmid.gsa: the gsa verb is not in this build yet (docs/gsa.md); "
                              "phasmid.read() loads /gsa files")
