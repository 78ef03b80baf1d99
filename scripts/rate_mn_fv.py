#!/usr/bin/python3
"""f-V curve of phasmid's Traub motoneuron, the source of the rate MN's R(V) (docs/model.md,
"Rate motoneurons").

One spiking MN (phasmid's defaults, Tables A.5-A.9 with docs/model.md's changes) with the
adaptation gate frozen at m_q, driven by an extra conductance g_x towards 0 mV (excitation) or
-80 mV (inhibition, the IN -> MN synapse). For each drive: the tonic firing rate, the mean
spike-driven muscle activation of (2.83)/(2.84) and the mean m_q,inf(V), against the passive
("would-be") potential Vp that the rate MN's V stands for. Then a least-squares fit of
f = 100 Hz (softplus_w(Vp - V_th) / dV_ref)^p over the operating range Vp < -55 mV.

Usage: /usr/bin/python3 scripts/rate_mn_fv.py [m_q]   (numpy only; RK4, 0.005 ms; ~3 CPU min)
"""
import sys

import numpy as np

C, gNa, ENa, gK, EK, gq, Eq, gL, EL, gapp, Eapp = 1.0, 10, 55, 2, -80, 12, -80, 0.8, -70, 0.4, 0
V_hq, s_q = -30, -0.6
A0, B, V_SPIKE, SPIKE_W = 2.0, 0.02, -20, 2.0  # muscle.a0, muscle.b, muscle.V_spike, muscle.spike_width


def exprel(x, c):  # x / (exp(c x) - 1), removable singularity avoided
    x = np.where(np.abs(x) < 1e-7, 1e-7, x)
    return x / (np.exp(c * x) - 1)


def rhs(y, mq, gx, Ex):
    V, m, h, n = y
    am, bm = 0.32 * exprel(-51.9 - V, 0.25), -0.28 * exprel(-24.9 - V, -0.20)
    ah, bh = 0.128 * np.exp(0.056 * (-48 - V)), 4.0 / (np.exp(0.2 * (-25 - V)) + 1)
    an, bn = 0.016 * exprel(-29.9 - V, 0.2), 0.25 * np.exp(0.025 * (-45 - V))
    I = (gNa * m * m * h * (V - ENa) + gK * n * (V - EK) + gq * mq * (V - Eq) + gL * (V - EL) +
         gapp * (V - Eapp) + gx * (V - Ex))
    return np.array([-I / C, am * (1 - m) - bm * m, ah * (1 - h) - bh * h, an * (1 - n) - bn * n])


def fv_curve(mq, t_end=2000.0, t_discard=500.0, dt=0.005):
    gx = np.concatenate([np.linspace(0.3, 0.0, 31), np.linspace(0.0, 0.3, 31)[1:]])
    Ex = np.concatenate([np.full(31, -80.0), np.full(30, 0.0)])
    y = np.array([np.full(len(gx), v) for v in (-60.0, 0.05, 0.6, 0.1)])
    a = np.zeros(len(gx))
    spikes, a_sum, q_sum, n = np.zeros(len(gx)), np.zeros(len(gx)), np.zeros(len(gx)), 0
    above = np.zeros(len(gx), bool)
    for k in range(int(t_end / dt)):
        k1 = rhs(y, mq, gx, Ex)
        k2 = rhs(y + dt / 2 * k1, mq, gx, Ex)
        k3 = rhs(y + dt / 2 * k2, mq, gx, Ex)
        k4 = rhs(y + dt * k3, mq, gx, Ex)
        y = y + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        S = 1 / (1 + np.exp(-(y[0] - V_SPIKE) / SPIKE_W))
        a = a + dt * ((A0 + B) * S * (1 - a) - B * (1 - S) * a)
        now = y[0] > V_SPIKE
        if k * dt > t_discard:
            spikes += now & ~above
            a_sum += a
            q_sum += 1 / (1 + np.exp(s_q * (y[0] - V_hq)))
            n += 1
        above = now
    Vp = (gq * mq * Eq + gL * EL + gapp * Eapp + gx * Ex) / (gq * mq + gL + gapp + gx)
    return Vp, spikes / ((t_end - t_discard) / 1000), a_sum / n, q_sum / n


def rate_model(x, V):
    V_th, w, p, dV = x
    z = (V - V_th) / w
    sp = w * np.where(z > 30, z, np.log1p(np.exp(np.minimum(z, 30))))
    return 100 * (sp / dV) ** p


def nelder_mead(f, x0, steps, iterations=3000):
    n = len(x0)
    S = [np.array(x0, float)] + [np.array(x0, float) + np.eye(n)[i] * steps[i] for i in range(n)]
    F = [f(s) for s in S]
    for _ in range(iterations):
        o = np.argsort(F)
        S, F = [S[i] for i in o], [F[i] for i in o]
        c = np.mean(S[:-1], 0)
        xr = c + (c - S[-1])
        fr = f(xr)
        if fr < F[0]:
            xe = c + 2 * (c - S[-1])
            fe = f(xe)
            S[-1], F[-1] = (xe, fe) if fe < fr else (xr, fr)
        elif fr < F[-2]:
            S[-1], F[-1] = xr, fr
        else:
            xc = c + 0.5 * (S[-1] - c)
            fc = f(xc)
            if fc < F[-1]:
                S[-1], F[-1] = xc, fc
            else:
                S = [S[0]] + [S[0] + 0.5 * (s - S[0]) for s in S[1:]]
                F = [f(s) for s in S]
    return S[0], F[0]


if __name__ == "__main__":
    mq = float(sys.argv[1]) if len(sys.argv) > 1 else 0.045
    Vp, f, a, q = fv_curve(mq)
    for row in zip(Vp, f, a, q):
        print("Vp %.3f mV  f %.1f Hz  mean a %.3f  mean m_q,inf %.4f" % row)
    op = Vp < -55  # operating range: a disinhibited MN sits near -57 mV
    cost = lambda x: 1e9 if min(x[1], x[2], x[3]) <= 0 else np.sum((rate_model(x, Vp[op]) - f[op]) ** 2)
    x, c = nelder_mead(cost, [-59.2, 0.05, 0.4, 2.2], [0.1, 0.02, 0.1, 0.3])
    print("f = 100 Hz (softplus_w(Vp - V_th)/dV_ref)^p: V_th %.3f mV, w %.4f mV, p %.4f, dV_ref %.3f mV, rms %.2f Hz"
          % (x[0], x[1], x[2], x[3], np.sqrt(c / op.sum())))
    firing = op & (f > 0)
    print("per spike: activation rate a/(1-a) b / f = %.2f-%.2f, mean m_q,inf / f = %.2e-%.2e per Hz"
          % tuple(np.r_[np.percentile(a[firing] / (1 - a[firing]) * B / (f[firing] / 1000), [5, 95]),
                        np.percentile(q[firing] / f[firing], [5, 95])]))
