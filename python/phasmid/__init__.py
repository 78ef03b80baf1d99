"""phasmid from Python: scenarios, simulations, sensitivities, fits, sweeps and global
sensitivity analyses of the stick-insect walking model, on the same C++ core as the
``phasmid`` command (docs/python.md).

    import phasmid
    run = phasmid.load("configs/single_joint_fti.toml").simulate(t_end_ms=4000)
    run.angles["middle"]["fti"], run.features["period_ms"]

Runs release the GIL (threads run scenarios in parallel), Ctrl-C interrupts them, errors
raise phasmid.Error and its subclasses with the CLI's one-line messages, and trajectories
are NumPy views of the C++ result's memory (read-only, no copy).
"""
from ._core import Error, ConfigError, SolverError, __version__
from ._results import (Parameter, Parameters, Feature, Features, Event, Result,
                       SimulationResult, SensitivityResult, FitResult, SweepResult,
                       GsaResult, GsaFeature, FileResult, read)
from ._scenario import Scenario, load, loads, fit, sweep, gsa

__all__ = [
    "Error", "ConfigError", "SolverError", "__version__",
    "Scenario", "load", "loads", "fit", "sweep", "gsa", "read",
    "Parameter", "Parameters", "Feature", "Features", "Event",
    "Result", "SimulationResult", "SensitivityResult", "FitResult", "SweepResult", "GsaResult", "GsaFeature",
    "FileResult",
]

Error.__doc__ = ("Base of every phasmid error; str(e) is the one-line message the CLI prints "
                 "after 'phasmid: error: '.")
ConfigError.__doc__ = "A config, section, option or parameter name/value that phasmid rejects."
SolverError.__doc__ = "A numerical failure of an integration or optimisation."
