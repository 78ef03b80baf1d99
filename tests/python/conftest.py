"""Fixtures of the Python API tests (docs/python.md): the CLI binary and the source tree, given
by ctest through PHASMID_BINARY and PHASMID_SOURCE_DIR (tests/CMakeLists.txt); and what the
interrupt tests use to see that a run is under way without assuming how fast it goes."""
import ctypes
import os
import queue
import signal
import subprocess
import sys
import threading
import time

import h5py
import numpy as np
import pytest

SOURCE_DIR = os.environ.get("PHASMID_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
BINARY = os.environ.get("PHASMID_BINARY", os.path.join(SOURCE_DIR, "build", "phasmid"))
HERE = os.path.dirname(os.path.abspath(__file__))
# A hang guard, not a speed limit: only a process that is stuck takes this long to show a sign.
HANG_SECONDS = 300


def config(name):
    """Path of a shipped config."""
    return os.path.join(SOURCE_DIR, "configs", name)


def cli(*args, check=True):
    """Run the phasmid binary; returns the CompletedProcess (text)."""
    r = subprocess.run([BINARY, *args], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError("phasmid %s failed: %s" % (" ".join(args), r.stderr))
    return r


def h5_datasets(path):
    """{"/group/name": array} of every numeric dataset of a file."""
    out = {}

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset) and obj.dtype.kind in "fiu":
            out["/" + name] = obj[()]

    with h5py.File(path, "r") as f:
        f.visititems(visit)
    return out


def assert_same_bits(a, b, what=""):
    """Exact equality, NaN equal to NaN (bit for bit for doubles)."""
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape, "%s: shape %s vs %s" % (what, a.shape, b.shape)
    if a.dtype == np.float64 and b.dtype == np.float64:
        a, b = np.ascontiguousarray(a).view(np.uint64), np.ascontiguousarray(b).view(np.uint64)
    assert np.array_equal(a, b), what


@pytest.fixture(scope="session")
def binary():
    assert os.access(BINARY, os.X_OK), "no phasmid binary at %s (set PHASMID_BINARY)" % BINARY
    return BINARY


_libc = ctypes.CDLL(None, use_errno=True)


def sigint_c_handler():
    """The C-level SIGINT handler installed now, as an address (sigaction(2) with no new action;
    glibc's struct sigaction starts with the handler pointer). While a run is inside C++,
    phasmid's own handler replaces Python's: InterruptGuard (python/src/bindings.hpp) for a
    simulation, installed before the GIL is released and removed after it is taken back; the
    sweep engine's (src/sweep/sweep_runner.cpp) for a sweep or gsa, installed with the GIL
    released, before the first point. A change of this value is the sign that a run is under
    way."""
    old = ctypes.create_string_buffer(256)  # larger than glibc's struct sigaction (152 bytes)
    if _libc.sigaction(signal.SIGINT, None, old) != 0:
        raise OSError(ctypes.get_errno(), "sigaction")
    return ctypes.c_void_p.from_buffer(old).value or 0


def print_running_when_guarded():
    """For a child process: start a thread that prints "running" as soon as phasmid's SIGINT
    handler replaces the one installed now, i.e. once the next run is inside C++ (call it just
    before the run)."""
    before = sigint_c_handler()

    def watch():
        while sigint_c_handler() == before:
            time.sleep(0.001)
        print("running", flush=True)

    threading.Thread(target=watch, daemon=True).start()


class Child:
    """`python -c script args...` with this directory on its path (so that it can import
    conftest), its output lines read as they come."""

    def __init__(self, script, *args):
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join(p for p in (HERE, env.get("PYTHONPATH")) if p)
        self.p = subprocess.Popen([sys.executable, "-c", script, *args], stdout=subprocess.PIPE,
                                  stderr=subprocess.PIPE, text=True, env=env)
        self.lines, self.out, self.err = queue.Queue(), [], []
        self.readers = [threading.Thread(target=self._read, args=(self.p.stdout, self.out, True), daemon=True),
                        threading.Thread(target=self._read, args=(self.p.stderr, self.err, False), daemon=True)]
        for r in self.readers:
            r.start()

    def _read(self, stream, into, queued):
        for line in stream:
            into.append(line)
            if queued:
                self.lines.put(line)
        if queued:
            self.lines.put(None)

    def wait_for_line(self, want):
        """Block until the child prints the line `want`; fails if it ends first or hangs."""
        deadline = time.monotonic() + HANG_SECONDS
        while True:
            try:
                line = self.lines.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                self.p.kill()
                raise AssertionError("hung: no line %r from the child in %d s; stdout: %s"
                                     % (want, HANG_SECONDS, "".join(self.out)))
            if line is None:
                self.p.wait()
                raise AssertionError("the child ended (rc %s) before printing %r; stdout: %s stderr: %s"
                                     % (self.p.returncode, want, "".join(self.out), "".join(self.err)))
            if line.strip() == want:
                return

    def finish(self):
        """(returncode, stdout, stderr) once the child has ended; fails if it hangs."""
        try:
            self.p.wait(timeout=HANG_SECONDS)
        except subprocess.TimeoutExpired:
            self.p.kill()
            self.p.wait()
            raise AssertionError("hung: the child did not end within %d s" % HANG_SECONDS)
        for r in self.readers:
            r.join()
        return self.p.returncode, "".join(self.out), "".join(self.err)
