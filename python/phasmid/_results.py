"""Result objects of phasmid runs and files (docs/python.md)."""
import io
import os
import stat
import tempfile
from collections import namedtuple

import numpy as np

from . import _core

Parameter = namedtuple("Parameter", "name value unit source description lower upper")
Parameter.__doc__ = ("One model parameter: name, value, unit, cited source, one-line description and "
                     "admissible range [lower, upper].")
Feature = namedtuple("Feature", "name value unit")
Feature.__doc__ = "One gait feature: name, value and unit (docs/features.md)."
Event = namedtuple("Event", "t_ms state direction")
Event.__doc__ = ("A located event of a run: time (ms), the state whose root was crossed (features: an "
                 "angular velocity crossing zero, a leg angle crossing its contact threshold) and the "
                 "direction (+1 rising, -1 falling).")


class Parameters(list):
    """The parameters of a scenario, in the model's order: a list of Parameter records that can
    also be indexed by name (``params["middle.fti.k_E.flexion"].value``)."""

    def __getitem__(self, key):
        if isinstance(key, str):
            for p in self:
                if p.name == key:
                    return p
            raise KeyError(key)
        return list.__getitem__(self, key)

    @property
    def names(self):
        """Parameter names, in order."""
        return [p.name for p in self]

    @property
    def values(self):
        """Parameter values as a NumPy array, in order."""
        return np.array([p.value for p in self])

    def as_dict(self):
        """{name: value}."""
        return {p.name: p.value for p in self}


class Features(dict):
    """Gait features as {name: value}; ``.units[name]`` is the unit and ``.records`` the list
    of Feature(name, value, unit) in the order the run reported them."""

    def __init__(self, records):
        records = [Feature(*r) for r in records]
        super().__init__((r.name, r.value) for r in records)
        self.records = records
        self.units = {r.name: r.unit for r in records}


def _shown(value):
    """A value as a message shows it: its repr, cut short (10**400 has 401 digits)."""
    r = repr(value)
    return r if len(r) <= 40 else r[:37] + "..."


def _path(what, path, key="path"):
    """A str or os.PathLike as a str path; anything else is a phasmid.Error naming `key`."""
    if not isinstance(path, (str, os.PathLike)):
        raise _core.Error("%s: '%s' must be a path (str or os.PathLike), got %s" % (what, key, _shown(path)))
    path = os.fspath(path)
    if not isinstance(path, str) or not path or "\0" in path:
        raise _core.Error("%s: '%s' must be a non-empty str path without NUL, got %s" % (what, key, _shown(path)))
    return path


_KINDS = ((stat.S_ISDIR, "a directory"), (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
          (stat.S_ISFIFO, "a fifo"), (stat.S_ISSOCK, "a socket"))


def _read_bytes(path):
    """The bytes of a regular file, read in one bounded step (its size when opened): a
    directory, a device (/dev/zero never ends) or a fifo (never begins) is refused before
    anything is read, as the C++ readers refuse them (io::read_text_file)."""
    def refuse(reason):
        raise _core.Error("%s: cannot read: %s" % (path, reason))

    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)  # a fifo must not block the open
    except OSError as e:
        refuse(e.strerror)
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            refuse("it is %s; phasmid reads only regular files"
                   % next((name for test, name in _KINDS if test(st.st_mode)), "not a regular file"))
        chunks, left = [], st.st_size
        while left > 0:
            chunk = os.read(fd, min(left, 1 << 24))
            if not chunk:
                break
            chunks.append(chunk)
            left -= len(chunk)
    except OSError as e:
        refuse(e.strerror)
    finally:
        os.close(fd)
    if left:
        refuse("it shrank while being read")
    return b"".join(chunks)


def _one_line(e):
    text = " ".join(str(e).split())
    return text[:200] if text else type(e).__name__


def _load_h5(path, content):
    """Every dataset of a phasmid HDF5 file (its bytes `content`, read from `path`) as
    {"/group/name": array or str list} and every attribute as {"/group": {name: value}}; a file
    HDF5 cannot read is a phasmid.Error naming `path`."""
    import h5py

    data, attrs = {}, {}

    def convert(v):
        if isinstance(v, bytes):
            return v.decode()
        if isinstance(v, np.ndarray) and v.dtype.kind in "OS":
            return [x.decode() if isinstance(x, bytes) else x for x in v.tolist()]
        return v

    # A dataset may declare any extent in a few bytes: the limit of the C++ readers
    # (H5Reader::check_extent, docs/reliability.md) before anything is allocated for it.
    limit = max(64 * 1024 * 1024, 1000 * len(content))

    def visit(name, obj):
        key = "/" + name
        if obj.attrs:
            attrs[key] = {k: convert(v) for k, v in obj.attrs.items()}
        if isinstance(obj, h5py.Dataset):
            if obj.size * 8 > limit:
                raise _core.Error("%s: dataset %s declares %d values, more than a %d-byte file holds"
                                 % (path, key, obj.size, len(content)))
            data[key] = convert(obj[()])

    # From the bytes already read: the path is opened once, by _read_bytes.
    try:
        with h5py.File(io.BytesIO(content), "r") as f:
            attrs["/"] = {k: convert(v) for k, v in f.attrs.items()}
            f.visititems(visit)
    except _core.Error:
        raise
    except Exception as e:  # h5py's OSError, RuntimeError ("Object visitation failed"), ...
        raise _core.Error("%s: not a readable HDF5 file (%s)" % (path, _one_line(e))) from None
    return data, attrs


class Result:
    """Base of every phasmid result: ``.save(path)`` writes the HDF5 file the CLI writes for the
    same run, ``.report(path)`` the HTML report ``phasmid report`` makes of it; ``model`` and
    ``config`` are the file's root attributes (the model kind, the resolved config text)."""

    attrs = {}

    @property
    def config(self):
        """The resolved config text (config plus overrides) the result was made from."""
        return self.attrs.get("/", {}).get("config")

    @property
    def model(self):
        """The model kind that produced the result (None where a file does not record one)."""
        return self.attrs.get("/", {}).get("model")

    _made = None  # the C++ result of a run made here (it writes its own file)
    _file = None  # the FileResult of a file read back
    _inputs = ()  # the files the result came from (config, data, the file read): never overwritten

    def save(self, path):
        """Write the result as the phasmid HDF5 file (docs/hdf5.md) the CLI writes for the same
        run, through the same C++ writer; returns `path`. The path is checked as the CLI checks
        -o (io::check_output_path): not the config or data the result came from, not a
        directory, device, fifo or a symlink to one; a refused save writes nothing."""
        if self._made is not None:
            self._made.save(_path("save()", path))
        else:
            self._file.save(path)
        return path

    def report(self, path):
        """Write the self-contained HTML report of this result to `path` (checked as save()
        checks its path); returns `path`."""
        out = _path("report()", path)
        _core.check_output_path(out, list(self._inputs))
        with tempfile.TemporaryDirectory(prefix="phasmid-") as d:
            h5 = os.path.join(d, "result.h5")
            self.save(h5)
            _core.write_report(h5, out)
        return path


class FileResult(Result):
    """A result carried by the HDF5 file the C++ core wrote (fits, sweeps, files read back).

    ``data`` maps dataset paths ("/fit/estimate") to NumPy arrays (lists for strings),
    ``attrs`` maps object paths ("/", "/trajectory") to their attributes; ``model`` is the root
    attribute `model` where the file has one, ``config`` the resolved config text."""

    def __init__(self, path, inputs=None, file=None):
        if file is not None:  # the same file, read once (read())
            self._bytes, self._inputs, self.data, self.attrs = file._bytes, file._inputs, file.data, file.attrs
            return
        path = _path("read()", path)
        self._bytes = _read_bytes(path)
        self._inputs = [path] if inputs is None else list(inputs)
        self.data, self.attrs = _load_h5(path, self._bytes)

    def group(self, prefix):
        """{name below prefix: array} for every dataset under `prefix` ("/features")."""
        prefix = prefix.rstrip("/") + "/"
        return {k[len(prefix):]: v for k, v in self.data.items() if k.startswith(prefix)}

    def save(self, path):
        """Write the file as the C++ core wrote it (byte for byte), after the CLI's check of the
        path (Result.save), through path + ".tmp" and a rename as the C++ writer does; returns
        `path`."""
        _core.save_bytes(_path("save()", path), self._bytes, list(self._inputs))
        return path

    @property
    def features(self):
        """Features of the file's /features group as Features (name -> value, .units)."""
        units = {k: (self.attrs.get("/features/" + k) or {}).get("units", "")
                 for k in self.group("/features")}
        def scalar(v):
            v = np.asarray(v).reshape(-1)
            return float(v[0]) if v.dtype.kind in "fiu" else (v[0] if v.size == 1 else v.tolist())

        return Features([(k, scalar(v), units[k]) for k, v in self.group("/features").items()])

    def __repr__(self):
        return "<phasmid.%s: %d datasets>" % (type(self).__name__, len(self.data))


def _nested_angles(flat):
    out = {}
    for key, arr in flat.items():
        leg, joint = key.rsplit(".", 1) if "." in key else key.split("/", 1)
        out.setdefault(leg, {})[joint] = arr
    return out


class SimulationResult(Result):
    """One run of a scenario (Scenario.simulate, or a simulate file read back).

    ``time`` (ms), ``angles[leg][joint]`` (deg), ``angular_velocity[leg][joint]`` (deg/s) and
    ``states[name]`` (unit in ``state_units[name]``) are NumPy arrays; for a run made here
    they are read-only views of the C++ result (``y`` is the whole times x states matrix).
    ``features`` is a Features dict, ``events`` a list of Event records."""

    def __init__(self, sim=None, file=None, attrs=None, inputs=()):
        self._made, self._file = sim, file
        self.attrs = attrs or {}
        self._inputs = list(inputs) if sim is not None else file._inputs
        if sim is not None and sim.has_solution:
            return  # attributes are made on first access (__getattr__): a loop of runs pays for what it reads
        if sim is not None:  # a kind without an ODE trajectory: what its file holds
            with tempfile.TemporaryDirectory(prefix="phasmid-") as d:
                sim.save(os.path.join(d, "run.h5"))
                file = FileResult(os.path.join(d, "run.h5"))
            self._file = file
            self.notes, self.summary = sim.notes(), sim.summary()
        self._from_file(file)
        if sim is not None:
            self.features = Features(sim.feature_records())

    def __getattr__(self, name):
        sim = self.__dict__.get("_made")
        make = _SIMULATION_ATTRIBUTES.get(name)
        if make is None or sim is None or not sim.has_solution:
            raise AttributeError(name)
        value = make(self, sim)
        setattr(self, name, value)
        return value

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(_SIMULATION_ATTRIBUTES))

    def _from_file(self, f):
        self.time = f.data.get("/trajectory/time")
        self.states = f.group("/trajectory/states")
        self.state_units = {k: f.attrs.get("/trajectory/states/" + k, {}).get("units", "") for k in self.states}
        self.angles = _group_tree(f.group("/trajectory/angles"))
        self.angular_velocity = _group_tree(f.group("/trajectory/angular_velocity"))
        self.features = f.features
        self.events = []
        self.data = f.data
        self.attrs = f.attrs
        self.notes, self.summary = getattr(self, "notes", []), getattr(self, "summary", "")

    def angle(self, name):
        """The angle "<leg>.<joint>" (deg)."""
        leg, joint = name.rsplit(".", 1)
        return self.angles[leg][joint]

    def __repr__(self):
        return "<phasmid.SimulationResult: %s>" % (self.summary or "%d times" % len(self.time))


def _degrees(sim, prefix):
    return _nested_angles({n[len(prefix):]: sim.degrees(n) for n in sim.degree_names() if n.startswith(prefix)})


def _events(sim):
    names, roots = sim.state_names, sim.root_states()
    return [Event(t, names[roots[root]], d) for t, root, d in sim.event_records()]


# How each attribute of a SimulationResult run here is made from the C++ Simulation.
_SIMULATION_ATTRIBUTES = {
    "time": lambda r, sim: sim.time,
    "y": lambda r, sim: sim.y,
    "states": lambda r, sim: {n: r.y[:, i] for i, n in enumerate(sim.state_names)},
    "state_units": lambda r, sim: dict(zip(sim.state_names, sim.state_units)),
    "angles": lambda r, sim: _degrees(sim, "angles/"),
    "angular_velocity": lambda r, sim: _degrees(sim, "angular_velocity/"),
    "features": lambda r, sim: Features(sim.feature_records()),
    "events": lambda r, sim: _events(sim),
    "notes": lambda r, sim: sim.notes(),
    "summary": lambda r, sim: sim.summary(),
}


def _group_tree(flat):
    out = {}
    for key, arr in flat.items():
        leg, _, joint = key.partition("/")
        out.setdefault(leg, {})[joint] = arr
    return out


class SensitivityResult(Result):
    """Forward sensitivities (Scenario.sensitivity, or a sensitivity file read back).

    ``absolute`` and ``relative`` are features x parameters arrays (axes labelled by
    ``feature_names`` and ``parameters``: ``axes["absolute"] == ("feature", "parameter")``);
    ``trajectory`` is times x states x parameters (labels ``time``, ``state_names``,
    ``parameters``), None when trajectory=False. For a run made here they are views of the
    C++ report. ``features`` holds the nominal feature values, ``ranking[feature]`` the
    parameters by |relative| sensitivity. ``mode`` says what was differentiated:
    "steady_cycle" (the converged gait cycle; ``cycle_period_ms`` its period) or "transient"
    (the run's window; ``mode_note`` says why when the automatic mode fell back to it)."""

    axes = {"absolute": ("feature", "parameter"), "relative": ("feature", "parameter"),
            "trajectory": ("time", "state", "parameter"), "states": ("time", "state")}

    def __init__(self, sens=None, file=None, attrs=None, inputs=()):
        self._made, self._file = sens, file
        self.attrs = attrs or {}
        self._inputs = list(inputs) if sens is not None else file._inputs
        if sens is not None:
            self.parameters = sens.parameters
            self.parameter_units = sens.parameter_units
            self.parameter_values = np.array(sens.parameter_values)
            self.features = Features(sens.feature_records())
            self.feature_names = [r.name for r in self.features.records]
            self.absolute, self.relative = sens.absolute, sens.relative
            self.time, self.trajectory, self.states = sens.time, sens.trajectory, sens.states
            self.state_names, self.state_units = sens.state_names, sens.state_units
            self.ranking = dict(zip(self.feature_names, sens.ranking))
            self.method, self.summary = sens.method, sens.summary()
            self.mode, self.mode_note, self.cycle_period_ms = sens.mode, sens.mode_note, sens.cycle_period_ms
        else:
            self._from_file(file)

    def _from_file(self, f):
        d = f.data
        self.parameters = d["/sensitivity/parameters"]
        self.parameter_units = d.get("/sensitivity/parameter_units", [])
        self.parameter_values = d.get("/sensitivity/parameter_values")
        self.feature_names = d.get("/sensitivity/feature_names") or list(f.group("/sensitivity/features"))
        self.features = Features(zip(self.feature_names, np.asarray(d["/sensitivity/feature_values"]).tolist(),
                                     d["/sensitivity/feature_units"])) if "/sensitivity/feature_values" in d else f.features
        self.absolute = np.array([f.data["/sensitivity/features/" + n] for n in self.feature_names]).reshape(
            len(self.feature_names), len(self.parameters))
        self.relative = np.array([f.data["/sensitivity/relative/" + n] for n in self.feature_names]).reshape(
            len(self.feature_names), len(self.parameters))
        self.ranking = {n: f.data.get("/sensitivity/ranking/" + n) for n in self.feature_names}
        self.time = d.get("/sensitivity/time")
        self.trajectory = d.get("/sensitivity/trajectory")
        self.state_names = d.get("/sensitivity/state_names", [])
        self.state_units = d.get("/sensitivity/state_units", [])
        self.states = None
        self.method = (f.attrs.get("/sensitivity") or {}).get("method")
        self.mode = (f.attrs.get("/sensitivity") or {}).get("mode")
        self.mode_note = (f.attrs.get("/sensitivity") or {}).get("mode_note", "")
        period = d.get("/sensitivity/cycle/period_ms")
        self.cycle_period_ms = float(np.asarray(period).ravel()[0]) if period is not None else None
        self.summary = ""
        self.data, self.attrs = f.data, f.attrs

    def d(self, feature, parameter, relative=False):
        """dF/dp of `feature` by `parameter` (or p/F dF/dp with relative=True)."""
        a = self.relative if relative else self.absolute
        return float(a[self.feature_names.index(feature), self.parameters.index(parameter)])


class FitResult(FileResult):
    """A fit (phasmid.fit, or a fit file read back): everything of the file's /fit group in
    ``data``; ``estimates`` {name: value}, ``standard_errors`` {name: value}, ``units``,
    ``final_cost``, ``converged`` (best start), ``summary`` (the text `phasmid fit` prints)."""

    def __init__(self, path, outcome=None, inputs=None, file=None):
        super().__init__(path, inputs, file)
        names = self.data["/fit/parameter_names"]
        self.parameter_names = names
        self.estimates = dict(zip(names, self.data["/fit/estimate"].tolist()))
        self.standard_errors = dict(zip(names, self.data["/fit/standard_error"].tolist()))
        self.units = dict(zip(names, self.data["/fit/parameter_units"]))
        self.final_cost = float(self.data["/fit/final_cost"])
        self.cost_history = self.data["/fit/cost_history"]
        conv = self.data.get("/fit/multistart/converged")
        best = (self.attrs.get("/fit/multistart") or {}).get("best", 0)
        self.converged = bool(outcome["converged"]) if outcome else (bool(conv[int(best)]) if conv is not None else None)
        summary = self.data.get("/fit/summary")
        self.summary = outcome["summary"] if outcome else (summary if isinstance(summary, str) else "")

    def __repr__(self):
        return "<phasmid.FitResult: %s, cost %g>" % (
            ", ".join("%s=%.6g" % kv for kv in self.estimates.items()), self.final_cost)


class SweepResult(FileResult):
    """A sweep (phasmid.sweep, or a sweep file read back): ``parameter_names``, ``points``
    (points x parameters), ``features`` {name: array over points}, ``status`` and
    ``gait_class`` per point, everything else of /sweep in ``data``."""

    def __init__(self, path, outcome=None, inputs=None, file=None):
        super().__init__(path, inputs, file)
        self.parameter_names = self.data["/sweep/parameter_names"]
        self.parameter_units = self.data.get("/sweep/parameter_units", [])
        self.points = self.data["/sweep/points"].reshape(-1, len(self.parameter_names))
        self._features = self.group("/sweep/features")
        self.status = self.data.get("/sweep/status")
        self.gait_class = self.data.get("/sweep/gait_class")
        self.outcome = outcome or {}

    @property
    def features(self):
        """{feature name: array over the points} (NaN where a point failed)."""
        return self._features

    def __repr__(self):
        return "<phasmid.SweepResult: %d points x %d parameters, %d features>" % (
            self.points.shape[0], self.points.shape[1], len(self.features))


class GsaFeature:
    """The analysis of one feature in a GsaResult (/gsa/<feature>, docs/gsa.md): ``name``,
    ``unit``, ``Y`` (the feature at every design row, NaN where undefined or failed), the counts
    ``n_nonfinite``, ``n_dropped`` and ``n_used`` (base rows or trajectories), and the indices
    over the parameters: Sobol' ``S1``, ``S1_conf``, ``ST``, ``ST_conf`` and, with second_order,
    ``S2``, ``S2_conf`` (D x D, upper triangle), ``variance``; Morris ``mu``, ``mu_star``,
    ``mu_star_conf``, ``sigma`` (None where the method has no such index). ``convergence``
    maps "n" and the index names to the nested-subset arrays (rows: subset sizes)."""

    INDICES = ("S1", "S1_conf", "ST", "ST_conf", "S2", "S2_conf", "mu", "mu_star", "mu_star_conf", "sigma")

    def __init__(self, result, name):
        g = "/gsa/" + name
        attrs = result.attrs.get(g, {})
        self.name = name
        self.unit = attrs.get("units", "")
        self.Y = result.data[g + "/Y"]
        for k in self.INDICES:
            setattr(self, k, result.data.get(g + "/" + k))
        self.n_nonfinite, self.n_dropped, self.n_used = (int(attrs[k]) for k in ("n_nonfinite", "n_dropped", "n_used"))
        self.variance = float(attrs["variance"]) if "variance" in attrs else None
        self.convergence = result.group(g + "/convergence")

    def __repr__(self):
        return "<phasmid.GsaFeature %s: %d used, %d dropped>" % (self.name, self.n_used, self.n_dropped)


class GsaResult(FileResult):
    """A global sensitivity analysis (phasmid.gsa, or a /gsa file read back; docs/gsa.md):
    ``method`` ("sobol" | "morris"), ``N`` (Sobol' base rows) or ``r`` (Morris trajectories),
    ``estimators`` {index: estimator name}; the design: ``parameter_names``,
    ``parameter_units``, ``lower``, ``upper``, ``scale``, ``design`` (rows x D, in parameter
    units) and ``unit_design`` (rows x D, unit cube); ``features`` {name: GsaFeature} with the
    outputs, the indices and the dropped-point counts; ``summary`` the table `phasmid gsa`
    prints (for a run made here). Everything of the file is in ``data`` and ``attrs``."""

    def __init__(self, path, outcome=None, inputs=None, file=None):
        super().__init__(path, inputs, file)
        a = self.attrs.get("/gsa", {})
        self.method = a.get("method")
        self.N = int(a["N"]) if "N" in a else None
        self.r = int(a["r"]) if "r" in a else None
        self.estimators = {k[len("estimator_"):]: v for k, v in a.items() if k.startswith("estimator_")}
        d = self.data
        self.parameter_names = d["/gsa/design/parameter_names"]
        self.parameter_units = d["/gsa/design/parameter_units"]
        self.scale = d["/gsa/design/scale"]
        self.lower, self.upper = d["/gsa/design/lower"], d["/gsa/design/upper"]
        dim = len(self.parameter_names)
        self.design = d["/gsa/design/values"].reshape(-1, dim)
        self.unit_design = d["/gsa/design/unit"].reshape(-1, dim)
        names = sorted({k.split("/")[2] for k in d if k.startswith("/gsa/") and k.split("/")[2] != "design"})
        self._features = {n: GsaFeature(self, n) for n in names}
        self.outcome = outcome or {}
        self.summary = self.outcome.get("summary", "")

    @property
    def features(self):
        """{feature name: GsaFeature}."""
        return self._features

    def __repr__(self):
        return "<phasmid.GsaResult: %s over %d parameters, %d design rows, %d features>" % (
            self.method, len(self.parameter_names), self.design.shape[0], len(self.features))


def read(path):
    """Load any phasmid HDF5 file into the result object of the verb that wrote it:
    SensitivityResult (/sensitivity), FitResult (/fit), GsaResult (/gsa), SweepResult (/sweep),
    SimulationResult (/trajectory), else a FileResult. Only a regular file is read (in one
    bounded step); a file that is not a complete phasmid file is a phasmid.Error naming it. The
    result's save() and report() may not overwrite `path`."""
    f = FileResult(path)
    path = _path("read()", path)
    keys = f.data.keys()
    try:
        if any(k.startswith("/sensitivity/") for k in keys):
            return SensitivityResult(file=f)
        if "/fit/parameter_names" in keys:
            return FitResult(path, file=f)
        if "/gsa/design/parameter_names" in keys:  # a gsa file holds its sweep too
            return GsaResult(path, file=f)
        if "/sweep/parameter_names" in keys:
            return SweepResult(path, file=f)
        if "/trajectory/time" in keys:
            return SimulationResult(file=f)
    except (KeyError, ValueError, TypeError, IndexError, AttributeError) as e:
        raise _core.Error("%s: not a complete phasmid file (%s: %s)" % (path, type(e).__name__, _one_line(e))) from None
    return f
