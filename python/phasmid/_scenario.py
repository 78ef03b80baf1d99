"""Scenarios and the analyses run on them (docs/python.md)."""
import numbers
import os
import tempfile

from . import _core
from ._results import (Parameter, Parameters, SimulationResult, SensitivityResult, FitResult,
                       SweepResult, GsaResult, _shown, _path)


def _refuse(what, message):
    """phasmid.ConfigError "<what>: <message>" (one line), for a keyword of the wrong type: the
    values themselves are checked by the C++ core, through the config's own checks."""
    raise _core.ConfigError("%s: %s" % (what, message))


def _number(what, key, value):
    """A keyword's value as a finite float: ints and floats (NumPy's too), not bools or text."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        _refuse(what, "'%s' must be a number, got %s" % (key, _shown(value)))
    try:
        v = float(value)
    except OverflowError:
        _refuse(what, "'%s' = %s is beyond the range of a double" % (key, _shown(value)))
    if v != v or v in (float("inf"), float("-inf")):
        _refuse(what, "'%s' must be a finite number, got %s" % (key, _shown(value)))
    return v


def _integer(what, key, value, lo=None):
    """A keyword's value as an int (not a bool, a float or text), at least `lo`."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        _refuse(what, "'%s' must be an integer, got %s" % (key, _shown(value)))
    value = int(value)
    if lo is not None and value < lo:
        _refuse(what, "'%s' = %d must be >= %d" % (key, value, lo))
    return value


def _flag(what, key, value):
    if not isinstance(value, bool):
        _refuse(what, "'%s' must be True or False, got %s" % (key, _shown(value)))
    return value


def _names(what, key, values):
    """A list of names from a list or tuple of str (a bare str would be its characters)."""
    if isinstance(values, (str, bytes)) or not isinstance(values, (list, tuple)):
        _refuse(what, "'%s' must be a list of names, got %s" % (key, _shown(values)))
    for v in values:
        if not isinstance(v, str):
            _refuse(what, "'%s' must be a list of names, got the element %s" % (key, _shown(v)))
    return list(values)


def _sets(values):
    """{name: value} or ["name=value", ...] as the --set assignments of the CLI (repr keeps
    every bit of a float); anything else is refused naming the parameter."""
    if values is None:
        return []
    if isinstance(values, dict):
        for k in values:
            if not isinstance(k, str):
                _refuse("set", "parameter names must be strings, got %s" % _shown(k))
        return ["%s=%r" % (k, _number("set", k, v)) for k, v in values.items()]
    if isinstance(values, (list, tuple)):
        for v in values:
            if not isinstance(v, str):
                _refuse("set", "a list of 'NAME=VALUE' strings is expected, got the element %s" % _shown(v))
        return list(values)
    _refuse("set", "expected {name: value} or a list of 'NAME=VALUE' strings, got %s" % _shown(values))


def _threads(what, threads):
    t = _integer(what, "threads", threads)
    # The C++ core checks the range (parallel::bounded_threads); beyond a C int it cannot be passed.
    return max(min(t, 2 ** 31 - 1), -(2 ** 31))


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
        if values is not None and not isinstance(values, dict):
            _refuse("with_parameters()", "expected {name: value}, got %s" % _shown(values))
        values = dict(values or {}, **kv)
        return Scenario(self._core.with_sets(_sets(values)))

    def simulate(self, t_end_ms=None, **options):
        """Run the scenario as `phasmid simulate` does and return a SimulationResult.

        Options override [simulation]: t_end_ms, output_dt_ms, discard_ms, rtol, atol,
        max_step_ms, max_steps (solver steps per output interval). Raises SolverError when
        the integration fails."""
        if t_end_ms is not None:
            options["t_end_ms"] = t_end_ms
        options = {k: _number("simulate()", k, v) for k, v in options.items()}
        return SimulationResult(self._core.simulate(options), attrs=self._attrs(), inputs=self._core.inputs)

    def sensitivity(self, parameters=None, method=None, t_end_ms=None, output_dt_ms=None,
                    discard_ms=None, trajectory=None, mode=None):
        """Sensitivities as `phasmid sensitivity` computes them: the config's
        [sensitivity] section (or the [simulation] run without one), overridden by the
        arguments (parameters: names; method: "forward" or "fd"; mode: "auto", "steady_cycle"
        or "transient"; trajectory: keep the times x states x parameters sensitivities of a
        transient run). Returns a SensitivityResult."""
        w = "sensitivity()"
        opt = lambda k, v, f: None if v is None else f(w, k, v)
        return SensitivityResult(_core.sensitivity(
            self._core, opt("parameters", parameters, _names), opt("method", method, _text),
            opt("t_end_ms", t_end_ms, _number), opt("output_dt_ms", output_dt_ms, _number),
            opt("discard_ms", discard_ms, _number), opt("trajectory", trajectory, _flag),
            opt("mode", mode, _text)),
            attrs=self._attrs(), inputs=self._core.inputs)

    def _attrs(self):
        return {"/": {"model": self.kind, "config": self.config_text}}

    def __repr__(self):
        return "<phasmid.Scenario %s (%s), %d parameters>" % (
            self.path, self.kind, len(self._core.parameter_records()))


def load(path, set=None):
    """Load a scenario config (a file, or the name of a shipped config such as
    "configs/single_joint_fti.toml"); `set` gives parameter overrides ({name: value} or
    ["name=value"]), applied like --set. Raises ConfigError naming file:line."""
    return Scenario(_core.Scenario.load(_path("load()", path), _sets(set)))


def loads(text, set=None, origin="<string>"):
    """A scenario from TOML text; errors name `origin`:line. See load()."""
    return Scenario(_core.Scenario.loads(_text("loads()", "text", text), _text("loads()", "origin", origin), _sets(set)))


def _text(what, key, value):
    if not isinstance(value, str):
        _refuse(what, "'%s' must be a string, got %s" % (key, _shown(value)))
    return value


def _scenario_of(config, set, what):
    if isinstance(config, Scenario):
        return config._core.with_sets(_sets(set)) if set else config._core
    return _core.Scenario.load(_path(what, config, "config"), _sets(set))


def fit(config, set=None, profile=(), **options):
    """Run the fit of a config's [fit] section as `phasmid fit` does and return a FitResult
    carrying what the HDF5 file holds. `config` is a path or a Scenario; options are the
    CLI's: data, data_format, parameters, optimizer, multistart, seed, target_set,
    max_iterations, threads; `profile` lists parameters to profile. Options are checked by the
    CLI's own checks (fit::check_overrides): multistart=-1 is refused as --multistart -1 is."""
    core = _scenario_of(config, set, "fit()")
    profile = _names("fit()", "profile", profile)
    with tempfile.TemporaryDirectory(prefix="phasmid-") as d:
        out = os.path.join(d, "fit.h5")
        outcome = _core.fit(core, options, profile, out)
        return FitResult(out, outcome, inputs=outcome["inputs"])


def _run_sweep(what, run, result, config, set, threads, out, resume, stop_after):
    """sweep() and gsa(): into the caller's `out` (checked like -o, with its journal; resume=True
    continues its journal) or into a temporary directory that nothing outlives."""
    core = _scenario_of(config, set, what)
    threads = _threads(what, threads)
    resume = _flag(what, "resume", resume)
    stop_after = _integer(what, "_stop_after", stop_after, lo=-1)
    if out is not None:
        out = _path(what, out, "out")
        outcome = run(core, threads, resume, out, True, stop_after)
        return result(out, outcome, inputs=core.inputs)
    if resume:
        _refuse(what, "resume=True needs out= (the output whose journal it continues)")
    with tempfile.TemporaryDirectory(prefix="phasmid-") as d:
        tmp = os.path.join(d, "result.h5")
        outcome = run(core, threads, False, tmp, False, stop_after)
        return result(tmp, outcome, inputs=core.inputs)


def sweep(config, set=None, threads=0, out=None, resume=False, _stop_after=-1):
    """Run every point of a config's [sweep] section as `phasmid sweep` does (threads: 0 for
    OpenMP's default) and return a SweepResult. With `out` the file is written there (checked as
    the CLI checks -o) and the finished points are journalled in out + ".journal": Ctrl-C
    finishes the running points and raises KeyboardInterrupt, and a later call with
    resume=True continues. Without `out` the run is in a temporary directory and an
    interrupted one keeps nothing. (`_stop_after`: for tests, stop as if interrupted after that
    many new points, as the CLI's --stop-after; the call then raises phasmid.Error.)"""
    return _run_sweep("sweep()", _core.sweep, SweepResult, config, set, threads, out, resume, _stop_after)


def gsa(config, set=None, threads=0, out=None, resume=False, _stop_after=-1):
    """Run the global sensitivity analysis of a config's [gsa] section over its
    [[sweep.parameter]] ranges as `phasmid gsa` does (the same C++ function: the design's
    sweep, then the analysis of its file; threads: 0 for OpenMP's default) and return a
    GsaResult carrying what the HDF5 file holds. `config` is a path or a Scenario; `set` gives
    parameter overrides like --set; `out` and `resume` as for sweep(). Ctrl-C finishes the
    running points and raises KeyboardInterrupt."""
    return _run_sweep("gsa()", _core.gsa, GsaResult, config, set, threads, out, resume, _stop_after)
