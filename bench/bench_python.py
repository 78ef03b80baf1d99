#!/usr/bin/env python3
"""Cost of calling phasmid from Python (docs/benchmarks.md, "Python module"):

1. One single-joint simulation (configs/single_joint_fti.toml, 9000 ms): load + simulate +
   save from Python against `phasmid simulate` minus the process start (`phasmid --version`).
2. 100 short runs (100 ms each) in a Python loop against the same loop in C++
   (bench/bench_run_loop.cpp).

Each figure is the median of REPEATS repetitions. Prints the overhead as a ratio; the target
is < 5 %.

    PYTHONPATH=build/python /usr/bin/python3 bench/bench_python.py [BUILD_DIR=build] [REPEATS=7]
"""
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
BUILD = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.path.join(ROOT, "build")
REPEATS = int(sys.argv[2]) if len(sys.argv) > 2 else 7
sys.path.insert(0, os.path.join(BUILD, "python"))
import phasmid  # noqa: E402

CONFIG = os.path.join(ROOT, "configs", "single_joint_fti.toml")
BINARY = os.path.join(BUILD, "phasmid")


def wall(cmd):
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t0


def median_of(f):
    return statistics.median(f() for _ in range(REPEATS))


def single_run(tmp):
    out = os.path.join(tmp, "x.h5")
    start = median_of(lambda: wall([BINARY, "--version"]))
    cli = median_of(lambda: wall([BINARY, "simulate", CONFIG, "-q", "-o", out])) - start

    def python():
        t0 = time.perf_counter()
        phasmid.load(CONFIG).simulate().save(out)
        return time.perf_counter() - t0

    py = median_of(python)
    print("single run (9000 ms, load + simulate + save):")
    print("  phasmid simulate %.4f s - process start %.4f s = %.4f s" % (cli + start, start, cli))
    print("  Python           %.4f s   ratio %.3f (overhead %+.1f %%)" % (py, py / cli, 100 * (py / cli - 1)))
    return py / cli


def loop(n=100, t_end_ms=100.0):
    r = subprocess.run([os.path.join(BUILD, "bench", "bench_run_loop"), CONFIG, str(n), str(t_end_ms)],
                       check=True, capture_output=True, text=True)
    cpp = float(r.stdout.split()[3])
    s = phasmid.load(CONFIG)

    def python():
        t0 = time.perf_counter()
        for _ in range(n):
            s.simulate(t_end_ms=t_end_ms)
        return time.perf_counter() - t0

    py = median_of(python)
    cpp = statistics.median([cpp] + [float(subprocess.run(r.args, check=True, capture_output=True, text=True)
                                           .stdout.split()[3]) for _ in range(REPEATS - 1)])
    print("loop of %d runs of %g ms:" % (n, t_end_ms))
    print("  C++    %.4f s (%.3f ms per run)" % (cpp, 1e3 * cpp / n))
    print("  Python %.4f s (%.3f ms per run)   ratio %.3f (overhead %+.1f %%)" % (py, 1e3 * py / n, py / cpp,
                                                                               100 * (py / cpp - 1)))
    return py / cpp


if __name__ == "__main__":
    with tempfile.TemporaryDirectory(prefix="phasmid-bench-") as tmp:
        ratios = [single_run(tmp), loop()]
    worst = max(ratios)
    print("largest overhead: %+.1f %% (target < 5 %%): %s" % (100 * (worst - 1), "ok" if worst < 1.05 else "ABOVE"))
    sys.exit(0 if worst < 1.05 else 1)
