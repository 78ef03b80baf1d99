"""The GIL is released while C++ integrates, and Ctrl-C interrupts a run (docs/python.md)."""
import os
import signal
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

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


def test_two_threads_at_once_give_the_serial_bits():
    # One scenario run by two threads at once: a run never changes its scenario, so both give
    # the serial run's numbers to the last bit. (How much faster two threads are is the
    # machine's free cores as much as phasmid: bench/bench_python.py prints it.)
    s = phasmid.load(config("single_joint_fti.toml"))
    serial = one(s)
    with ThreadPoolExecutor(2) as pool:
        runs = list(pool.map(one, [s, s]))
    assert_same_bits(serial.y, runs[0].y)
    assert_same_bits(serial.y, runs[1].y)


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
