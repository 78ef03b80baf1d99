#!/usr/bin/python3
"""Joint calibration of the rate motoneurons on the middle leg and the three-leg tetrapod
(docs/model.md, "Rate motoneurons").

`phasmid fit` fits one config at a time; the middle leg (configs/fit_rate_motoneuron_leg.toml)
and the tetrapod (configs/fit_rate_motoneuron_three_legs.toml) pull the onset V_th in opposite
directions (-58.885 vs -59.007 mV). This script minimises the sum of the two configs' costs
(the same weighted residuals, 1/2 sum ((feature - target) / tolerance)^2, features from
`phasmid simulate` on the fits' 2 ms grid) with Nelder-Mead over V_th, log10 width,
log10 gain and the f-V exponent, starting from the f-V curve's values.

Usage: /usr/bin/python3 scripts/rate_mn_joint_fit.py [iterations]   (run from the repository
root after building; ~2.5 s per evaluation)
"""
import os
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np

from rate_mn_fv import nelder_mead  # the same simplex search as the f-V fit

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PHASMID = os.path.join(ROOT, "build", "phasmid")
CONFIGS = ["configs/fit_rate_motoneuron_leg.toml", "configs/fit_rate_motoneuron_three_legs.toml"]
NAMES = ["mn.rate.V_th", "mn.rate.width", "muscle.rate.gain", "mn.rate.exponent"]
# Start: the f-V curve of the spiking MN (scripts/rate_mn_fv.py; width: its upper bound).
START = [-59.189, np.log10(0.001), np.log10(0.13), 0.3696]
STEPS = [0.06, 0.2, 0.03, 0.05]
# The parameter table's bounds (phasmid refuses values outside them): the simplex is clipped.
LOWER = [-70.0, np.log10(0.0005), np.log10(1e-6), 0.05]
UPPER = [-30.0, np.log10(10.0), np.log10(10.0), 2.0]


def load(config):
    """The simulation part of a fit config (on the fit's output grid) and its targets."""
    text = open(os.path.join(ROOT, config)).read()
    fit = text[text.index("[fit]"):]
    sim = text[:text.index("[fit]")]
    dt = re.search(r"output_dt_ms = (\S+)", fit).group(1)
    sim = re.sub(r"output_dt_ms = \S+", "output_dt_ms = " + dt, sim)
    targets = re.findall(r'name = "(.*)"\nvalue = (\S+)\ntolerance = (\S+)', fit)
    return sim, [(n, float(v), float(t)) for n, v, t in targets]


def cost(sim, targets, values, workdir):
    cfg, out = os.path.join(workdir, "c.toml"), os.path.join(workdir, "o.h5")
    open(cfg, "w").write(sim)
    sets = sum([["--set", "%s=%.9g" % nv] for nv in zip(NAMES, values)], [])
    subprocess.run([PHASMID, "simulate", cfg, "-o", out, "-q"] + sets, check=True)
    with h5py.File(out) as f:
        return 0.5 * sum(((f["features/" + n][()] - v) / t) ** 2 for n, v, t in targets)


if __name__ == "__main__":
    iterations = int(sys.argv[1]) if len(sys.argv) > 1 else 60
    cases = [load(c) for c in CONFIGS]
    with tempfile.TemporaryDirectory() as work:
        def total(x):
            x = np.clip(x, LOWER, UPPER)
            values = [x[0], 10 ** x[1], 10 ** x[2], x[3]]
            costs = [cost(sim, targets, values, work) for sim, targets in cases]
            print(" ".join("%.6g" % v for v in values), "costs", " ".join("%.3f" % c for c in costs), flush=True)
            return sum(costs)
        x, c = nelder_mead(total, START, STEPS, iterations)
    x = np.clip(x, LOWER, UPPER)
    print("best:", " ".join("%s=%.6g" % nv for nv in zip(NAMES, [x[0], 10 ** x[1], 10 ** x[2], x[3]])), "sum %.3f" % c)
