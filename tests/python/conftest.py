"""Fixtures of the Python API tests (docs/python.md): the CLI binary and the source tree, given
by ctest through PHASMID_BINARY and PHASMID_SOURCE_DIR (tests/CMakeLists.txt)."""
import os
import subprocess

import h5py
import numpy as np
import pytest

SOURCE_DIR = os.environ.get("PHASMID_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
BINARY = os.environ.get("PHASMID_BINARY", os.path.join(SOURCE_DIR, "build", "phasmid"))


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
