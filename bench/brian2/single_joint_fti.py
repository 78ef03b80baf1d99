#!/usr/bin/python3
"""The isolated FTi single-joint network (configs/single_joint_fti.toml, 26 states) in Brian2,
written from docs/model.md ("A second implementation: the single-joint network"), run on
Brian2's C++ standalone device.

Usage (Debian's Python: apt-get install -y python3-brian python3-numpy libgsl-dev):
    /usr/bin/python3 bench/brian2/single_joint_fti.py --method rk4 --dt 0.01
    /usr/bin/python3 bench/brian2/single_joint_fti.py --method rkf45 --error 1e-3 --dt 0.1 --repeats 3
    (--method: rk4, or one of GSL_METHODS below: rkf45, rkck, rk8pd, rk2)

Prints one JSON object: the compile time (code generation and C++ build) apart from the run
times (the standalone binary's own CPU clock around the network run), and the features of
docs/features.md computed from the FTi angle over the window [discard_ms, t_end_ms]:
`fti.period_ms`, the mean extremal angles `fti.angle_min_deg`, `fti.angle_max_deg`,
`fti.flexion_fraction`.

All 26 states are one Brian2 NeuronGroup of size 1, so that RK4 and the GSL integrator step
the whole coupled system (Brian2 synapses would hold the synaptic currents constant over each
dt, a splitting error phasmid does not have). Variables are plain numbers in phasmid's units
(mV, ms, nS, pF, rad, rad/s), so each right-hand side is divided by `ms`.
"""
import argparse
import json
import math
import os
import resource
import sys
import tempfile
import time
import warnings

import numpy as np

# ---- parameters (docs/model.md; names as `phasmid params configs/single_joint_fti.toml`) ----
P = {
    # NaP kinetics shared by CPG neurons and interneurons; V_hh differs (CPG -44, IN -30 mV).
    "E_Na": 50.0, "V_hm": -37.0, "gamma_m": -1.0 / 6, "gamma_h": 1.0 / 6, "V_tau_h": -30.0,
    "gamma_tau": -1.0 / 12, "E_L": -65.0,
    "cpg.V_hh": -44.0, "interneuron.V_hh": -30.0,
    # FTi CPG (Tables A.1/A.2): epsilon in 1/ms, C_m in pF.
    "cpg.epsilon": 0.0023, "cpg.C_m": 0.9154, "cpg.g_NaP": 10.0, "cpg.g_L": 2.8, "cpg.E_app": 0.0,
    "cpg_flx.g_app": 0.100, "cpg_ext.g_app": 0.209,
    "interneuron.epsilon": 0.010, "interneuron.C_m": 0.210,
    "in.g_NaP": 10.0, "in.g_L": 2.8, "in.g_app": 1.6, "inhibitory.E_app": -80.0,
    "sens_inh.g_NaP": 10.0, "sens_inh.g_L": 6.8, "sens_inh.g_app": 2.0,
    "sens_exc.g_NaP": 5.0, "sens_exc.g_L": 10.0, "sens_exc.g_app": 0.60, "excitatory.E_app": 0.0,
    # Motoneuron (Tables A.5-A.9, with g_app 0.40 nS and E_q -80 mV).
    "mn.C_m": 1.0, "mn.g_Na": 10.0, "mn.E_Na": 55.0,
    "Na.a_m1": 0.32, "Na.a_m2": -51.9, "Na.a_m3": 0.25, "Na.b_m1": -0.28, "Na.b_m2": -24.9, "Na.b_m3": -0.20,
    "Na.a_h1": 0.128, "Na.a_h2": -48.0, "Na.a_h3": 0.056, "Na.b_h1": 4.0, "Na.b_h2": -25.0, "Na.b_h3": 0.20,
    "mn.g_K": 2.0, "mn.E_K": -80.0,
    "K.a_m1": 0.016, "K.a_m2": -29.9, "K.a_m3": 0.20, "K.b_m1": 0.25, "K.b_m2": -45.0, "K.b_m3": 0.025,
    "mn.g_q": 12.0, "mn.E_q": -80.0, "mn.V_hq": -30.0, "mn.s_q": -0.6, "mn.r_q": 0.0005,
    "mn.g_L": 0.8, "mn.E_L": -70.0, "mn.g_app": 0.40, "mn.E_app": 0.0,
    # Muscle activation.
    "muscle.a0": 2.0, "muscle.b": 0.02, "muscle.V_spike": -20.0, "muscle.spike_width": 2.0,
    # FTi mechanics (Tables A.10, A.14), time in seconds inside the acceleration.
    "d": 0.28, "l_E0": 1.41, "l_F0": 2.11, "l_E_min": 1.05, "l_F_min": 1.50, "h_E": 0.34, "h_F": 0.42,
    "inertia": 0.1008, "b_v": 12.5,
    "k_F.flexion": 296.0, "k_F.extension": 55.0, "k_E.flexion": 510.0, "k_E.extension": 4050.0,
    "gamma0": 77.5,
}

# Synapse classes of Table A.4: g (nS), V_h (mV), gamma (1/mV), E (mV).
SYN = {
    "cpg_cpg": (1.0, -43.0, -10.0, -80.0),
    "in_cpg_inh": (0.05, -43.0, -10.0, -80.0),
    "in_cpg_exc": (0.1, -43.0, -0.42, 0.0),
    "in_mn": (0.25, -43.0, -0.1, -80.0),
    "cpg_in": (0.5, -43.0, -10.0, 0.0),
}

# NaP neurons: name -> (g_NaP, g_L, g_app, E_app, epsilon, C_m, V_hh, V0, h0).
def nap_neurons(p):
    cpg = (p["cpg.g_NaP"], p["cpg.g_L"])
    cpg_k = (p["cpg.epsilon"], p["cpg.C_m"], p["cpg.V_hh"])
    in_k = (p["interneuron.epsilon"], p["interneuron.C_m"], p["interneuron.V_hh"])
    return {
        "cpg_flx": (*cpg, p["cpg_flx.g_app"], p["cpg.E_app"], *cpg_k, -60.0, 0.6),
        "cpg_ext": (*cpg, p["cpg_ext.g_app"], p["cpg.E_app"], *cpg_k, -30.0, 0.3),
        "in_flx": (p["in.g_NaP"], p["in.g_L"], p["in.g_app"], p["inhibitory.E_app"], *in_k, -70.0, 0.9),
        "in_ext": (p["in.g_NaP"], p["in.g_L"], p["in.g_app"], p["inhibitory.E_app"], *in_k, -70.0, 0.9),
        "sens_exc": (p["sens_exc.g_NaP"], p["sens_exc.g_L"], p["sens_exc.g_app"], p["excitatory.E_app"], *in_k, -70.0, 0.9),
        "sens_inh": (p["sens_inh.g_NaP"], p["sens_inh.g_L"], p["sens_inh.g_app"], p["inhibitory.E_app"], *in_k, -70.0, 0.9),
    }

MOTONEURONS = ["mn_flx", "mn_ext"]
# The nine synapses of the FTi joint network: (pre, post, class).
SYNAPSES = [
    ("cpg_flx", "cpg_ext", "cpg_cpg"), ("cpg_ext", "cpg_flx", "cpg_cpg"),
    ("cpg_ext", "in_flx", "cpg_in"), ("cpg_flx", "in_ext", "cpg_in"),
    ("in_flx", "mn_flx", "in_mn"), ("in_ext", "mn_ext", "in_mn"),
    ("sens_exc", "cpg_flx", "in_cpg_exc"), ("sens_exc", "sens_inh", "in_cpg_exc"),
    ("sens_inh", "cpg_ext", "in_cpg_inh"),
]


def f(x):
    return repr(float(x))


def boltz(V, V_half, slope):
    return f"1.0/(1.0 + exp({f(slope)}*({V} - ({f(V_half)}))))"


def synaptic_current(post, synapses=None):
    """Sum of (2.7) over the synapses onto `post`: (pre, post, (g, V_h, gamma, E)) tuples,
    by default this network's SYNAPSES with their Table A.4 classes."""
    if synapses is None:
        synapses = [(pre, q, SYN[cls]) for pre, q, cls in SYNAPSES]
    terms = [f"{f(g)}*{boltz('V_' + pre, Vh, gam)}*(V_{post} - ({f(E)}))" for pre, q, (g, Vh, gam, E) in synapses if q == post]
    return " + ".join(terms) if terms else "0.0"


def nap_equations(name, q, p, synapses=None, extra_drive=None):
    """extra_drive: an expression (nS) added to g_app (modulations)."""
    g_NaP, g_L, g_app, E_app, eps, C_m, V_hh, _, _ = q
    V = "V_" + name
    drive = f"({f(g_app)} + {extra_drive})" if extra_drive else f(g_app)
    m_inf = boltz(V, p["V_hm"], p["gamma_m"])
    h_inf = boltz(V, V_hh, p["gamma_h"])
    return [
        f"dV_{name}/dt = -({f(g_NaP)}*{m_inf}*h_{name}*({V} - ({f(p['E_Na'])})) + {f(g_L)}*({V} - ({f(p['E_L'])}))"
        f" + I_{name} + {drive}*({V} - ({f(E_app)})))/{f(C_m)}/ms : 1",
        f"dh_{name}/dt = {f(eps)}*({h_inf} - h_{name})*cosh({f(p['gamma_tau'])}*({V} - ({f(p['V_tau_h'])})))/ms : 1",
        f"I_{name} = {synaptic_current(name, synapses)} : 1",
    ]


def mn_equations(n, p, synapses=None):
    V = "V_" + n

    def exprel_ratio(scale, V0, c):
        # scale (V0 - V) / (exp(c (V0 - V)) - 1) = scale / (c exprel(c (V0 - V)))
        return f"{f(scale)}/({f(c)}*exprel({f(c)}*({f(V0)} - {V})))"

    a_m = exprel_ratio(p["Na.a_m1"], p["Na.a_m2"], p["Na.a_m3"])
    b_m = exprel_ratio(p["Na.b_m1"], p["Na.b_m2"], p["Na.b_m3"])
    a_h = f"{f(p['Na.a_h1'])}*exp({f(p['Na.a_h3'])}*({f(p['Na.a_h2'])} - {V}))"
    b_h = f"{f(p['Na.b_h1'])}/(exp({f(p['Na.b_h3'])}*({f(p['Na.b_h2'])} - {V})) + 1.0)"
    a_k = exprel_ratio(p["K.a_m1"], p["K.a_m2"], p["K.a_m3"])
    b_k = f"{f(p['K.b_m1'])}*exp({f(p['K.b_m3'])}*({f(p['K.b_m2'])} - {V}))"
    mq_inf = boltz(V, p["mn.V_hq"], p["mn.s_q"])
    return [
        f"dV_{n}/dt = -({f(p['mn.g_Na'])}*mNa_{n}**2*hNa_{n}*({V} - ({f(p['mn.E_Na'])}))"
        f" + {f(p['mn.g_K'])}*mK_{n}*({V} - ({f(p['mn.E_K'])}))"
        f" + {f(p['mn.g_q'])}*mq_{n}*({V} - ({f(p['mn.E_q'])}))"
        f" + {f(p['mn.g_L'])}*({V} - ({f(p['mn.E_L'])})) + I_{n}"
        f" + {f(p['mn.g_app'])}*({V} - ({f(p['mn.E_app'])})))/{f(p['mn.C_m'])}/ms : 1",
        f"dmNa_{n}/dt = ({a_m}*(1.0 - mNa_{n}) - {b_m}*mNa_{n})/ms : 1",
        f"dhNa_{n}/dt = ({a_h}*(1.0 - hNa_{n}) - {b_h}*hNa_{n})/ms : 1",
        f"dmK_{n}/dt = ({a_k}*(1.0 - mK_{n}) - {b_k}*mK_{n})/ms : 1",
        f"dmq_{n}/dt = {f(p['mn.r_q'])}*({mq_inf} - mq_{n})/ms : 1",
        f"I_{n} = {synaptic_current(n, synapses)} : 1",
    ]


def muscle_and_joint_equations(p):
    a0, b, Vs, w = p["muscle.a0"], p["muscle.b"], p["muscle.V_spike"], p["muscle.spike_width"]
    eqs = []
    for mus, mn in (("flx", "mn_flx"), ("ext", "mn_ext")):
        S = f"1.0/(1.0 + exp(-(V_{mn} - ({f(Vs)}))/{f(w)}))"
        eqs.append(f"da_{mus}/dt = ({f(a0 + b)}*S_{mus}*(1.0 - a_{mus}) - {f(b)}*(1.0 - S_{mus})*a_{mus})/ms : 1")
        eqs.append(f"S_{mus} = {S} : 1")
    # Spring constants: k = k_rest + (k_active - k_rest) a; the flexor rests at its extension
    # value and is active at its flexion value, the extensor the other way round.
    kF0, kF1 = p["k_F.extension"], p["k_F.flexion"]
    kE0, kE1 = p["k_E.flexion"], p["k_E.extension"]
    eqs.append(f"k_F = {f(kF0)} + {f(kF1 - kF0)}*a_flx : 1")
    eqs.append(f"k_E = {f(kE0)} + {f(kE1 - kE0)}*a_ext : 1")
    d = p["d"]
    for m, shift, l0, h, lmin in (("E", f"{f(d)}*cos(ang)", p["l_E0"], p["h_E"], p["l_E_min"]),
                                  ("F", f"{f(-2 * d)}*cos(ang)", p["l_F0"], p["h_F"], p["l_F_min"])):
        c0 = math.sqrt(1.0 - (h / l0) ** 2)
        eqs.append(f"l_{m} = sqrt({f(l0 * l0)} + ({shift})**2 - {f(2 * l0 * c0)}*({shift})) : 1")
        eqs.append(f"F_{m} = k_{m}*(l_{m} - {f(lmin)})**2*sqrt(1.0 - ({f(h)}/l_{m})**2) : 1")
    I, bv = p["inertia"], p["b_v"]
    # (2.22) in rad/s^2 with time in s; the state equations convert to ms (1e-3).
    eqs.append(f"acc = {f(d / I)}*((2.0*F_F - F_E)*sin(ang) - {f(5 * bv * d)}*omg) : 1")
    eqs.append("dang/dt = 1e-3*omg/ms : 1")
    eqs.append("domg/dt = 1e-3*acc/ms : 1")
    return eqs


def build_equations(p):
    lines = []
    for name, q in nap_neurons(p).items():
        lines += nap_equations(name, q, p)
    for n in MOTONEURONS:
        lines += mn_equations(n, p)
    lines += muscle_and_joint_equations(p)
    return "\n".join(lines)


def initial_state(p):
    init = {}
    for name, q in nap_neurons(p).items():
        init["V_" + name], init["h_" + name] = q[7], q[8]
    for n in MOTONEURONS:
        init.update({"V_" + n: -65.0, "mNa_" + n: 0.02, "hNa_" + n: 0.98, "mK_" + n: 0.05, "mq_" + n: 0.0})
    init.update({"a_flx": 0.0, "a_ext": 0.0, "ang": math.radians(p["gamma0"]), "omg": 0.0})
    return init


# ---- features of docs/features.md from the sampled angle ----------------------------------
def extrema(t, ang, omg):
    """Velocity zeros located within each sample interval by the cubic Hermite interpolant of
    the angle (values and derivatives at both ends). Returns (time ms, angle deg, is_max)."""
    out = []
    dt = np.diff(t)
    s = np.sign(omg)
    for i in np.nonzero(s[:-1] * s[1:] < 0)[0]:
        h = dt[i]
        y0, y1 = ang[i], ang[i + 1]
        d0, d1 = omg[i] * 1e-3 * h, omg[i + 1] * 1e-3 * h  # rad per interval
        # Hermite derivative on u in [0,1]: p'(u) = A u^2 + B u + C
        A = 6 * y0 + 3 * d0 - 6 * y1 + 3 * d1
        B = -6 * y0 - 4 * d0 + 6 * y1 - 2 * d1
        C = d0
        if abs(A) < 1e-300:
            u = -C / B
        else:
            disc = max(B * B - 4 * A * C, 0.0)
            roots = [(-B + sg * math.sqrt(disc)) / (2 * A) for sg in (1, -1)]
            u = min(roots, key=lambda r: abs(r - 0.5))
        u = min(max(u, 0.0), 1.0)
        h00, h10, h01, h11 = 2 * u**3 - 3 * u**2 + 1, u**3 - 2 * u**2 + u, -2 * u**3 + 3 * u**2, u**3 - u**2
        y = h00 * y0 + h10 * d0 + h01 * y1 + h11 * d1
        out.append((t[i] + u * h, math.degrees(y), omg[i] > 0))
    return out


def turning_points(ext, discard_ms, min_swing_deg=0.5, min_swing_fraction=0.3):
    """The turning points of the gait cycle after the discard time, as src/features/features.cpp
    selects them (docs/features.md): peak detection with hysteresis delta = max(0.5 deg, 0.3 x
    the range of the extrema after discard_ms) over the whole run."""
    late = [e[1] for e in ext if e[0] >= discard_ms]
    if not late:
        return []
    delta = max(min_swing_deg, min_swing_fraction * (max(late) - min(late)))
    kept, looking, imax, imin = [], 0, 0, 0
    for k, (_, v, is_max) in enumerate(ext):
        if is_max and looking >= 0 and (v > ext[imax][1] or not ext[imax][2]):
            imax = k
        if not is_max and looking <= 0 and (v < ext[imin][1] or ext[imin][2]):
            imin = k
        if looking >= 0 and ext[imax][2] and v < ext[imax][1] - delta:
            kept.append(ext[imax])
            looking, imin = -1, k
        elif looking <= 0 and not ext[imin][2] and v > ext[imin][1] + delta:
            kept.append(ext[imin])
            looking, imax = 1, k
    return [e for e in kept if e[0] >= discard_ms]


def features(t, ang, omg, discard_ms):
    tp = turning_points(extrema(t, ang, omg), discard_ms)
    mx = [e for e in tp if e[2]]
    mn = [e for e in tp if not e[2]]
    res = {"n_max": len(mx), "n_min": len(mn)}
    if len(mx) >= 2:
        res["period_ms"] = (mx[-1][0] - mx[0][0]) / (len(mx) - 1)
    if mx:
        res["angle_max_deg"] = float(np.mean([e[1] for e in mx]))
    if mn:
        res["angle_min_deg"] = float(np.mean([e[1] for e in mn]))
    rise = [b[0] - a[0] for a, b in zip(tp, tp[1:]) if not a[2] and b[2]]
    if rise and "period_ms" in res:
        res["flexion_fraction"] = float(np.mean(rise)) / res["period_ms"]
    return res


# ---- Brian2 ---------------------------------------------------------------------------------
# GSL steps allowed per clock dt (Brian2's default, 100, makes tight error bounds fail at
# dt = 1 ms during MN spikes).
GSL_MAX_STEPS = 100000
# Brian2's adaptive GSL steppers (method "gsl_<name>"): Runge-Kutta-Fehlberg 4(5), Cash-Karp
# 4(5), Prince-Dormand 8(9) and the embedded 2(3) pair.
GSL_METHODS = ["rkf45", "rkck", "rk8pd", "rk2"]


class stdout_to_stderr:
    """Redirects file descriptor 1 (also of child processes such as make) to 2."""

    def __enter__(self):
        sys.stdout.flush()
        self.saved = os.dup(1)
        os.dup2(2, 1)

    def __exit__(self, *exc):
        sys.stdout.flush()
        os.dup2(self.saved, 1)
        os.close(self.saved)


def patch_gsl_standalone():
    """Brian2 2.5.1 (Debian 12) derives its GSL standalone code object from CodeObject instead
    of CPPStandaloneCodeObject, so `method='gsl_*'` fails with "Implement compile_block
    method"; later Brian2 releases derive it from CPPStandaloneCodeObject, as here."""
    from brian2.devices.cpp_standalone.codeobject import CPPStandaloneCodeObject
    from brian2.devices.cpp_standalone.GSLcodeobject import GSLCPPStandaloneCodeObject as G

    if issubclass(G, CPPStandaloneCodeObject):
        return
    base_init = G.__init__

    def init(self, *args, **kwds):
        base_init(self, *args, **kwds)
        self.before_after_blocks = []

    G.__init__ = init
    for name in ("__call__", "compile_block", "run_block"):
        setattr(G, name, CPPStandaloneCodeObject.__dict__[name])


def parse_args(doc, argv=None):
    ap = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    ap.add_argument("--method", choices=["rk4"] + GSL_METHODS, default="rk4")
    ap.add_argument("--dt", type=float, default=0.01, help="clock dt, ms (RK4 step; GSL: output interval)")
    ap.add_argument("--error", type=float, default=1e-3, help="GSL absolute error bound (all variables)")
    ap.add_argument("--sample-dt", type=float, default=0.1, help="angle sampling interval, ms")
    ap.add_argument("--t-end", type=float, default=9000.0, help="simulated time, ms")
    ap.add_argument("--discard", type=float, default=2000.0, help="features from this time on, ms")
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--dir", default="", help="standalone project directory (default: a new temporary one)")
    ap.add_argument("--print-equations", action="store_true")
    return ap.parse_args(argv)


def simulate(a, eqs, init, channels, name):
    """Builds the one-group model on the standalone device, compiles it, runs it a.repeats times
    and returns the JSON answer: times, and per channel j -> (angle var, velocity var) the
    features `j.<feature>` (or "error" if the integration blew up)."""
    warnings.simplefilter("ignore")  # Debian's pythran/numpy deprecation noise on import
    import brian2 as b2

    b2.prefs.logging.file_log = False
    b2.prefs.logging.std_redirection = False
    directory = a.dir or tempfile.mkdtemp(prefix=f"brian2_{name}_")
    b2.set_device("cpp_standalone", directory=directory, build_on_run=False)
    patch_gsl_standalone()
    b2.prefs.devices.cpp_standalone.extra_make_args_unix = ["-j1"]
    b2.defaultclock.dt = a.dt * b2.ms
    if a.method == "rk4":
        method, options = "rk4", {}
    else:
        method, options = "gsl_" + a.method, {"absolute_error": a.error, "max_steps": GSL_MAX_STEPS}
    G = b2.NeuronGroup(1, eqs, method=method, method_options=options, name=name)
    for k, v in init.items():
        setattr(G, k, v)
    recorded = [v for pair in channels.values() for v in pair]
    mon = b2.StateMonitor(G, recorded, record=0, dt=max(a.sample_dt, a.dt) * b2.ms, name="angles")
    b2.run(a.t_end * b2.ms)
    t0 = time.perf_counter()
    with stdout_to_stderr():  # the compiler's output is not part of the JSON answer
        b2.device.build(directory=directory, compile=True, run=False, with_output=False)
    res = {"method": a.method, "dt_ms": a.dt, "compile_s": time.perf_counter() - t0, "run_cpu_s": [],
           "process_cpu_s": [], "directory": directory}
    if a.method in GSL_METHODS:
        res["absolute_error"] = a.error
    for _ in range(a.repeats):
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        b2.device.run(directory, False, [])
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        res["run_cpu_s"].append(b2.device._last_run_time)  # std::clock() around the network run
        res["process_cpu_s"].append(r1.ru_utime + r1.ru_stime - r0.ru_utime - r0.ru_stime)
    res["run_cpu_s_min"] = min(res["run_cpu_s"])
    t = np.asarray(mon.t / b2.ms)
    for j, (va, vw) in channels.items():
        ang, omg = np.asarray(getattr(mon, va)[0]), np.asarray(getattr(mon, vw)[0])
        if not np.all(np.isfinite(ang)):
            return {"error": "non-finite angle (integration unstable)", "method": a.method, "dt_ms": a.dt}
        res.update({f"{j}.{k}": v for k, v in features(t, ang, omg, a.discard).items()})
    return res


def main():
    a = parse_args(__doc__)
    if a.print_equations:
        print(build_equations(P))
        return 0
    res = simulate(a, build_equations(P), initial_state(P), {"fti": ("ang", "omg")}, "fti")
    print(json.dumps(res))
    return 0 if "error" not in res else 1


if __name__ == "__main__":
    sys.exit(main())
