#!/usr/bin/python3
"""The isolated middle leg walking forward (configs/middle_leg_forward.toml: PR, LD and FE
joint networks with the sensory coupling of Section 3.2, ThC Table A.17; 24 neurons, 78
states) in Brian2, written from docs/model.md ("Networks"), on the C++ standalone device.

Usage as bench/brian2/single_joint_fti.py (same options and JSON output); the features are
per joint (`thc.*`, `ctr.*`, `fti.*`: period, mean extremal angles over [discard, t_end]).
"""
import json
import math
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import single_joint_fti as sj  # noqa: E402  (shared classes, MN equations, features, Brian2 helpers)

P = sj.P
f, boltz = sj.f, sj.boltz

# Per joint: CPG epsilon, C_m, inc/dec drives; sensory IN class; IN -> IN conductance; mechanics.
JOINTS = {
    "thc": dict(inc="ret", dec="pro", eps=0.0019, C_m=1.1493, g_inc=0.165, g_dec=0.205,
                sens=(5.0, 10.0, 0.60), g_in_in=2.0, angle0=78.0,
                mech=dict(d=2.0, r=2.5, l_dec_min=1.0, l_inc_min=1.5, I=0.288, b_v=25.5,
                          k_inc=(16.0, 429.0), k_dec=(25.0, 1000.0))),   # Table A.17 (rest, active)
    "ctr": dict(inc="lev", dec="dep", eps=0.0012, C_m=1.8308, g_inc=0.34, g_dec=0.14,
                sens=(7.0, 9.85, 0.29), g_in_in=0.1, angle0=60.0,
                mech=dict(d=3.5, r=1.0, l_inc_min=1.05, l_dec_min=1.50, I=0.9341, b_v=84.0,
                          k_inc=(879.21, 1868.1), k_dec=(160.0, 800.0))),  # Table A.15
    "fti": dict(inc="flx", dec="ext", eps=0.0023, C_m=0.9154, g_inc=0.100, g_dec=0.209,
                sens=(5.0, 10.0, 0.60), g_in_in=2.0, angle0=77.5,
                mech=dict(I=0.1008, b_v=12.5, k_inc=(55.0, 296.0), k_dec=(510.0, 4050.0))),  # Table A.14
}
W = 1.0  # width of the angle sigmoids, deg


def S_below(var, thr):
    return f"1.0/(1.0 + exp(-({f(thr)} - {var}*{f(180 / math.pi)})/{f(W)}))"


def S_above(var, thr):
    return f"1.0/(1.0 + exp(-({var}*{f(180 / math.pi)} - {f(thr)})/{f(W)}))"


def network():
    """Neurons (name -> NaP tuple or 'mn'), synapses (pre, post, (g, V_h, gamma, E)), extra drives."""
    nap, mns, syn = {}, [], []
    in_k = (P["interneuron.epsilon"], P["interneuron.C_m"], P["interneuron.V_hh"])
    for j, q in JOINTS.items():
        cpg_k = (q["eps"], q["C_m"], P["cpg.V_hh"])
        cpg = (P["cpg.g_NaP"], P["cpg.g_L"])
        n = {k: f"{j}_{k}" for k in ("cpg_inc", "cpg_dec", "in_inc", "in_dec", "sens_exc", "sens_inh", "mn_inc", "mn_dec")}
        nap[n["cpg_inc"]] = (*cpg, q["g_inc"], 0.0, *cpg_k, -60.0, 0.6)
        nap[n["cpg_dec"]] = (*cpg, q["g_dec"], 0.0, *cpg_k, -30.0, 0.3)
        nap[n["in_inc"]] = (10.0, 2.8, 1.6, -80.0, *in_k, -70.0, 0.9)
        nap[n["in_dec"]] = (10.0, 2.8, 1.6, -80.0, *in_k, -70.0, 0.9)
        nap[n["sens_exc"]] = (q["sens"][0], q["sens"][1], q["sens"][2], 0.0, *in_k, -70.0, 0.9)
        nap[n["sens_inh"]] = (10.0, 6.8, 2.0, -80.0, *in_k, -70.0, 0.9)
        mns += [n["mn_inc"], n["mn_dec"]]
        C = sj.SYN
        excited, inhibited = (n["cpg_dec"], n["cpg_inc"]) if j == "ctr" else (n["cpg_inc"], n["cpg_dec"])
        syn += [(n["cpg_inc"], n["cpg_dec"], C["cpg_cpg"]), (n["cpg_dec"], n["cpg_inc"], C["cpg_cpg"]),
                (n["cpg_dec"], n["in_inc"], C["cpg_in"]), (n["cpg_inc"], n["in_dec"], C["cpg_in"]),
                (n["in_inc"], n["mn_inc"], C["in_mn"]), (n["in_dec"], n["mn_dec"], C["in_mn"]),
                (n["sens_exc"], excited, C["in_cpg_exc"]),
                (n["sens_exc"], n["sens_inh"], (q["g_in_in"], -43.0, -0.42, 0.0)),
                (n["sens_inh"], inhibited, C["in_cpg_inh"])]
    # Sensory coupling: extra drive (nS) of the sensory INs.
    extra = {
        "thc_sens_exc": f"{f(3.90 - 0.60)}*{S_below('ang_ctr', 38.0)}",
        "fti_sens_exc": f"{f(3.00 - 0.60)}*{S_below('ang_ctr', 50.0)}"
                        f" + {f(1.90 - 3.00)}*{S_below('ang_ctr', 50.0)}*{S_above('ang_fti', 90.0)}",
        "ctr_sens_exc": f"{f(2.00 - 0.29)}*int(t >= 200.0*ms)",
    }
    return nap, mns, syn, extra


def joint_equations(j, q):
    a0, b, Vs, w = P["muscle.a0"], P["muscle.b"], P["muscle.V_spike"], P["muscle.spike_width"]
    eqs = []
    for side in ("inc", "dec"):
        mn = f"V_{j}_mn_{side}"
        eqs.append(f"da_{j}_{side}/dt = ({f(a0 + b)}*S_{j}_{side}*(1.0 - a_{j}_{side}) - {f(b)}*(1.0 - S_{j}_{side})*a_{j}_{side})/ms : 1")
        eqs.append(f"S_{j}_{side} = 1.0/(1.0 + exp(-({mn} - ({f(Vs)}))/{f(w)})) : 1")
        k0, k1 = q["mech"]["k_" + side]
        eqs.append(f"k_{j}_{side} = {f(k0)} + {f(k1 - k0)}*a_{j}_{side} : 1")
    m, A, Om = q["mech"], f"ang_{j}", f"omg_{j}"
    I, bv = m["I"], m["b_v"]
    if j == "fti":
        d = P["d"]
        for X, side, shift, l0, h, lmin in (("E", "dec", f"{f(d)}*cos({A})", P["l_E0"], P["h_E"], P["l_E_min"]),
                                            ("F", "inc", f"{f(-2 * d)}*cos({A})", P["l_F0"], P["h_F"], P["l_F_min"])):
            c0 = math.sqrt(1.0 - (h / l0) ** 2)
            eqs.append(f"l_{X} = sqrt({f(l0 * l0)} + ({shift})**2 - {f(2 * l0 * c0)}*({shift})) : 1")
            eqs.append(f"F_{X} = k_{j}_{side}*(l_{X} - {f(lmin)})**2*sqrt(1.0 - ({f(h)}/l_{X})**2) : 1")
        acc = f"{f(d / I)}*((2.0*F_F - F_E)*sin({A}) - {f(5 * bv * d)}*{Om})"
    elif j == "ctr":
        d, r = m["d"], m["r"]
        acc = (f"{f(r / I)}*(k_{j}_inc*({f(d - m['l_inc_min'])} - {f(r)}*{A})**2"
               f" - k_{j}_dec*({f(d - m['l_dec_min'])} + {f(r)}*{A})**2) - {f(bv * r * r / I)}*{Om}")
    else:
        d, r = m["d"], m["r"]
        eqs.append(f"l_R = sqrt({f(r * r + d * d)} + {f(2 * r * d)}*cos({A})) : 1")
        eqs.append(f"l_P = sqrt({f(r * r + d * d)} - {f(2 * r * d)}*cos({A})) : 1")
        acc = (f"{f(r * d / I)}*sin({A})*(k_{j}_inc*(l_R - {f(m['l_inc_min'])})**2/l_R"
               f" - k_{j}_dec*(l_P - {f(m['l_dec_min'])})**2/l_P) - {f(bv * d * d / I)}*{Om}")
    eqs.append(f"acc_{j} = {acc} : 1")
    eqs.append(f"d{A}/dt = 1e-3*{Om}/ms : 1")
    eqs.append(f"d{Om}/dt = 1e-3*acc_{j}/ms : 1")
    return eqs


def build_equations():
    nap, mns, syn, extra = network()
    lines = []
    for name, q in nap.items():
        lines += sj.nap_equations(name, q, P, syn, extra.get(name))
    for n in mns:
        lines += sj.mn_equations(n, P, syn)
    for j, q in JOINTS.items():
        lines += joint_equations(j, q)
    return "\n".join(lines), nap, mns


def initial_state(nap, mns):
    init = {}
    for name, q in nap.items():
        init["V_" + name], init["h_" + name] = q[7], q[8]
    for n in mns:
        init.update({"V_" + n: -65.0, "mNa_" + n: 0.02, "hNa_" + n: 0.98, "mK_" + n: 0.05, "mq_" + n: 0.0})
    for j, q in JOINTS.items():
        init.update({f"a_{j}_inc": 0.0, f"a_{j}_dec": 0.0, f"ang_{j}": math.radians(q["angle0"]), f"omg_{j}": 0.0})
    return init


def main():
    a = sj.parse_args(__doc__)
    eqs, nap, mns = build_equations()
    if a.print_equations:
        print(eqs)
        return 0
    channels = {j: (f"ang_{j}", f"omg_{j}") for j in JOINTS}
    res = sj.simulate(a, eqs, initial_state(nap, mns), channels, "leg")
    print(json.dumps(res))
    return 0 if "error" not in res else 1


if __name__ == "__main__":
    sys.exit(main())
