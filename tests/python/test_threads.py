"""The GIL is released while C++ integrates, and Ctrl-C interrupts a run (docs/python.md)."""
import os
import signal
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import pytest

import phasmid
from conftest import assert_same_bits, config

T_END_MS = 9000  # ~1 s of a single joint: long against thread start, short for the suite


def one(scenario):
    return scenario.simulate(t_end_ms=T_END_MS)


def test_python_threads_run_while_cpp_integrates():
    # With the GIL held during the run, this thread would stand still for the whole run.
    s = phasmid.load(config("single_joint_fti.toml"))
    with ThreadPoolExecutor(1) as pool:
        t0 = time.perf_counter()
        future = pool.submit(one, s)
        last, longest, ticks = t0, 0.0, 0
        while not future.done():
            now = time.perf_counter()
            longest, last, ticks = max(longest, now - last), now, ticks + 1
        duration = time.perf_counter() - t0
        future.result()
    assert duration > 0.2 and ticks > 1000
    assert longest < 0.25 * duration, (longest, duration)


def idle_cores(seconds=0.5):
    """Idle cores measured now from /proc/stat (the load average lags by a minute)."""
    def idle_and_total():
        ticks = [int(v) for v in open("/proc/stat").readline().split()[1:]]
        return ticks[3] + ticks[4], sum(ticks)
    i0, t0 = idle_and_total()
    time.sleep(seconds)
    i1, t1 = idle_and_total()
    cores = min(os.cpu_count() or 1, len(os.sched_getaffinity(0)))
    return cores * (i1 - i0) / max(1, t1 - t0)


def test_two_threads_run_in_parallel():
    # A wall-time claim needs two free cores; ctest runs this file alone (RUN_SERIAL), so it
    # is skipped only where something outside the suite keeps the machine busy.
    idle = idle_cores()
    if idle < 1.5:
        pytest.skip("needs two idle cores, %.1f idle" % idle)
    s = phasmid.load(config("single_joint_fti.toml"))
    one(s)  # warm-up
    serial, parallel = [], []
    for _ in range(2):  # best of two: the machine is shared
        t0 = time.perf_counter()
        one(s)
        serial.append(time.perf_counter() - t0)
        with ThreadPoolExecutor(2) as pool:
            t0 = time.perf_counter()
            runs = list(pool.map(one, [s, s]))
            parallel.append(time.perf_counter() - t0)
    assert_same_bits(runs[0].y, runs[1].y)
    # With the GIL held the two runs would take 2x one run; released, about 1x.
    assert min(parallel) < 1.6 * min(serial), (serial, parallel)


INTERRUPTED = r"""
import sys, time, phasmid
s = phasmid.load(sys.argv[1])
print("started", flush=True)
t0 = time.perf_counter()
try:
    s.simulate(t_end_ms=1e7, output_dt_ms=1000)
except KeyboardInterrupt as e:
    print("interrupted after %.2f s: %s" % (time.perf_counter() - t0, e), flush=True)
    s.simulate(t_end_ms=100)  # the next run is not affected
    print("next run ok", flush=True)
"""


def test_ctrl_c_interrupts_a_long_run():
    p = subprocess.Popen([sys.executable, "-c", INTERRUPTED, config("single_joint_fti.toml")],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=os.environ)
    assert p.stdout.readline().strip() == "started"
    time.sleep(1.0)
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=30)
    assert p.returncode == 0, err
    assert "interrupted after" in out and "interrupted at t = " in out and "next run ok" in out
