#!/usr/bin/env python3
"""Cost of calling phasmid from Python (docs/performance.md "Python"):

1. One single-joint simulation (configs/single_joint_fti.toml, 9000 ms): load + simulate +
   save from Python against `phasmid simulate` minus the process start (`phasmid --version`).
2. 100 short runs (100 ms each) in a Python loop against the same loop in C++
   (bench/bench_run_loop.cpp).
3. Two single-joint simulations on two Python threads against the same two one after the
   other (wall time): about 0.5 with two free cores, since every run releases the GIL; 1.0
   would mean the runs are serialised. Printed only: it measures the machine's free cores as
   much as phasmid.

Each figure is the median of REPEATS repetitions, as wall time and as CPU time (user + system;
on a shared machine the wall time also measures the other jobs). Prints the overhead as a
ratio; the target is < 5 %. Exit status 1 when the CPU-time overhead is above it.

    /usr/bin/python3 bench/bench_python.py [BUILD_DIR=build] [REPEATS=7]
"""
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
BUILD = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.path.join(ROOT, "build")
REPEATS = int(sys.argv[2]) if len(sys.argv) > 2 else 7
sys.path.insert(0, os.path.join(BUILD, "python"))
import phasmid  # noqa: E402

CONFIG = os.path.join(ROOT, "configs", "single_joint_fti.toml")
BINARY = os.path.join(BUILD, "phasmid")


def cpu(who):
    r = resource.getrusage(who)
    return r.ru_utime + r.ru_stime


def timed(f, who=resource.RUSAGE_SELF):
    """(wall, cpu) seconds of f(); who: RUSAGE_SELF, or RUSAGE_CHILDREN for subprocesses."""
    c0, t0 = cpu(who), time.perf_counter()
    f()
    return time.perf_counter() - t0, cpu(who) - c0


def median_of(f, who=resource.RUSAGE_SELF):
    runs = [timed(f, who) for _ in range(REPEATS)]
    return statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs)


def run_cli(*args):
    subprocess.run([BINARY, *args], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def line(label, py, ref):
    print("  %-34s wall %.4f s vs %.4f s: ratio %.3f   cpu %.4f s vs %.4f s: ratio %.3f" % (
        label, py[0], ref[0], py[0] / ref[0], py[1], ref[1], py[1] / ref[1]))
    return py[1] / ref[1], py[0] / ref[0]


def single_run(tmp):
    out = os.path.join(tmp, "x.h5")
    start = median_of(lambda: run_cli("--version"), resource.RUSAGE_CHILDREN)
    whole = median_of(lambda: run_cli("simulate", CONFIG, "-q", "-o", out), resource.RUSAGE_CHILDREN)
    cli = (whole[0] - start[0], whole[1] - start[1])
    py = median_of(lambda: phasmid.load(CONFIG).simulate().save(out))
    print("single run, 9000 ms (load + simulate + save); process start wall %.4f s, cpu %.4f s:" % start)
    return line("Python vs CLI minus process start", py, cli)


def loop(n=100, t_end_ms=100.0):
    def cpp_once():
        r = subprocess.run([os.path.join(BUILD, "bench", "bench_run_loop"), CONFIG, str(n), str(t_end_ms)],
                           check=True, capture_output=True, text=True).stdout.split()
        return float(r[3]), float(r[5])

    cpp_runs = [cpp_once() for _ in range(REPEATS)]
    cpp = statistics.median(r[0] for r in cpp_runs), statistics.median(r[1] for r in cpp_runs)
    s = phasmid.load(CONFIG)

    def python():
        for _ in range(n):
            s.simulate(t_end_ms=t_end_ms, discard_ms=0).features  # as the C++ loop reads them

    py = median_of(python)
    print("loop of %d runs of %g ms (%.3f ms per run in C++):" % (n, t_end_ms, 1e3 * cpp[0] / n))
    return line("Python loop vs C++ loop", py, cpp)


def two_threads():
    s = phasmid.load(CONFIG)

    def serial():
        s.simulate()
        s.simulate()

    def parallel():
        with ThreadPoolExecutor(2) as pool:
            list(pool.map(lambda _: s.simulate(), range(2)))

    ser, par = median_of(serial), median_of(parallel)
    print("two runs of 9000 ms on two threads against the same two in sequence:")
    print("  wall %.4f s vs %.4f s: ratio %.3f" % (par[0], ser[0], par[0] / ser[0]))


if __name__ == "__main__":
    print("load average %.1f on %d cores" % (os.getloadavg()[0], len(os.sched_getaffinity(0))))
    with tempfile.TemporaryDirectory(prefix="phasmid-bench-") as tmp:
        ratios = [single_run(tmp), loop()]
    two_threads()
    worst_cpu, worst_wall = max(r[0] for r in ratios), max(r[1] for r in ratios)
    print("largest overhead: cpu %+.1f %%, wall %+.1f %% (target < 5 %%): %s" % (
        100 * (worst_cpu - 1), 100 * (worst_wall - 1), "ok" if worst_cpu < 1.05 else "ABOVE"))
    sys.exit(0 if worst_cpu < 1.05 else 1)
