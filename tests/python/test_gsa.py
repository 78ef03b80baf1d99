"""phasmid.gsa() against `phasmid gsa` on the Ishigami config (docs/gsa.md, docs/python.md):
the same file bit for bit, read() of the CLI's file gives the same object, the analytic Sobol'
indices inside the estimates' intervals, Morris screening, the CLI's error messages and Ctrl-C."""
import os
import re
import signal
import tomllib

import h5py
import numpy as np
import pytest

import phasmid
from conftest import Child, assert_same_bits, cli, config, h5_datasets
from test_errors import cli_error

# Analytic Sobol' indices of the Ishigami function, a = 7, b = 0.1 (Sobol' & Levitan 1999),
# the values configs/gsa_ishigami.toml cites.
S1_EXACT = np.array([0.3139, 0.4424, 0.0])
ST_EXACT = np.array([0.5576, 0.4424, 0.2437])


def ishigami(tmp_path, **replace):
    """configs/gsa_ishigami.toml with [gsa] lines replaced (the suite's time budget)."""
    text = open(config("gsa_ishigami.toml")).read()
    for old, new in replace.items():
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / "gsa.toml"
    path.write_text(text)
    return str(path), text


def attributes(path):
    """{object path: {name: value}} of every group and dataset, the root's `command` and `created` left out."""
    out = {}

    def convert(v):
        return v.tolist() if isinstance(v, np.ndarray) else v

    with h5py.File(path, "r") as f:
        out["/"] = {k: convert(v) for k, v in f.attrs.items() if k not in ("command", "created")}
        f.visititems(lambda name, obj: out.__setitem__("/" + name, {k: convert(v) for k, v in obj.attrs.items()}))
    return out


def strings(path):
    """{dataset path: list of str} of every string dataset."""
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: out.__setitem__("/" + name, obj.asstr()[()].tolist())
                     if isinstance(obj, h5py.Dataset) and obj.dtype.kind in "OS" else None)
    return out


def assert_same_file(a, b):
    """Every dataset bit for bit, every attribute equal (the root's `command` and `created` aside)."""
    da, db = h5_datasets(a), h5_datasets(b)
    assert sorted(da) == sorted(db)
    for key in da:
        assert_same_bits(da[key], db[key], key)
    assert strings(a) == strings(b)
    assert attributes(a) == attributes(b)


@pytest.fixture(scope="module")
def sobol_pair(tmp_path_factory, binary):
    d = tmp_path_factory.mktemp("gsa")
    path, _ = ishigami(d, **{"N = 8192": "N = 1024"})
    printed = cli("gsa", path, "-j", "1", "-o", str(d / "ref.h5")).stdout
    return phasmid.gsa(path, threads=2), d / "ref.h5", printed


def test_gsa_equals_cli_file(sobol_pair, tmp_path):
    g, ref, printed = sobol_pair
    assert isinstance(g, phasmid.GsaResult) and g.method == "sobol" and g.N == 1024
    # N (2D + 2) rows with second order, D = 3.
    assert g.design.shape == (1024 * 8, 3) and g.unit_design.shape == (1024 * 8, 3)
    assert g.parameter_names == ["x1", "x2", "x3"] and list(g.features) == ["y"]
    assert g.estimators == {"S1": "Saltelli et al. 2010", "ST": "Jansen 1999", "S2": "Saltelli 2002"}
    assert_same_file(g.save(tmp_path / "py.h5"), ref)
    assert g.summary == printed and printed.startswith("y (1): 1024 of 1024 base rows used (0 non-finite")
    assert g.outcome["n_points"] == 8192 and g.outcome["n_failed"] == 0


def test_read_of_cli_file_is_the_same_object(sobol_pair):
    g, ref, _ = sobol_pair
    back = phasmid.read(ref)
    assert isinstance(back, phasmid.GsaResult)
    assert (back.method, back.N, back.r, back.estimators) == (g.method, g.N, g.r, g.estimators)
    assert back.parameter_names == g.parameter_names and back.scale == g.scale == ["lin"] * 3
    for key in ("design", "unit_design", "lower", "upper"):
        assert_same_bits(getattr(back, key), getattr(g, key), key)
    f, b = g.features["y"], back.features["y"]
    for key in ("Y",) + phasmid.GsaFeature.INDICES:
        if getattr(f, key) is None:
            assert getattr(b, key) is None and key in ("mu", "mu_star", "mu_star_conf", "sigma"), key
        else:
            assert_same_bits(getattr(b, key), getattr(f, key), key)
    assert (b.n_nonfinite, b.n_dropped, b.n_used, b.variance) == (f.n_nonfinite, f.n_dropped, f.n_used, f.variance)
    assert sorted(b.convergence) == sorted(f.convergence) == ["S1", "S1_conf", "ST", "ST_conf", "n"]
    assert f.convergence["n"].tolist() == [8, 16, 32, 64, 128, 256, 512, 1024]


def test_sobol_indices_near_analytic(sobol_pair):
    y = sobol_pair[0].features["y"]
    assert y.S2.shape == (3, 3) and y.n_used == 1024 and y.n_dropped == 0
    # Every analytic value inside the 95 % interval of its estimate (seeded: deterministic).
    assert np.all(np.abs(y.S1 - S1_EXACT) <= y.S1_conf), (y.S1, y.S1_conf)
    assert np.all(np.abs(y.ST - ST_EXACT) <= y.ST_conf), (y.ST, y.ST_conf)
    assert abs(y.S2[0, 2] - 0.2437) <= y.S2_conf[0, 2], (y.S2, y.S2_conf)
    assert np.all(y.S1_conf < 0.1) and np.all(y.ST_conf < 0.1)


def test_scenario_with_set_equals_cli(tmp_path, binary):
    # A Scenario from TOML text with a parameter override, against the CLI's --set.
    path, text = ishigami(tmp_path, **{"N = 8192": "N = 64", "second_order = true": "second_order = false"})
    cli("gsa", path, "-q", "-j", "1", "--set", "a=5", "-o", str(tmp_path / "ref.h5"))
    g = phasmid.gsa(phasmid.loads(text, origin=path), set={"a": 5}, threads=1)
    assert g.features["y"].S2 is None and g.design.shape == (64 * 5, 3)
    ref = h5_datasets(tmp_path / "ref.h5")
    saved = h5_datasets(g.save(tmp_path / "py.h5"))
    assert sorted(saved) == sorted(ref)
    for key in ref:
        assert_same_bits(saved[key], ref[key], key)
    # a = 5 changes the output: Y(x) = sin x1 + a sin^2 x2 + b x3^4 sin x1.
    x, y = g.design, g.features["y"].Y
    expect = np.sin(x[:, 0]) + 5 * np.sin(x[:, 1]) ** 2 + 0.1 * x[:, 2] ** 4 * np.sin(x[:, 0])
    assert np.allclose(y, expect, rtol=1e-12, atol=1e-12)


def test_morris_equals_cli(tmp_path, binary):
    path, _ = ishigami(tmp_path, **{'method = "sobol"': 'method = "morris"', "N = 8192": "trajectories = 20",
                                    "second_order = true": "levels = 4"})
    cli("gsa", path, "-q", "-j", "1", "-o", str(tmp_path / "ref.h5"))
    g = phasmid.gsa(path, threads=2)
    assert g.method == "morris" and g.r == 20 and g.N is None and g.design.shape == (20 * 4, 3)
    assert set(g.estimators) == {"mu", "mu_star"}
    y = g.features["y"]
    assert y.S1 is None and y.mu_star.shape == (3,) and y.n_used == 20
    # mean |EE| >= |mean EE| (equal, to rounding, where every effect has one sign).
    assert np.all(y.mu_star - np.abs(y.mu) >= -1e-12 * y.mu_star) and np.all(y.sigma >= 0)
    assert_same_file(g.save(tmp_path / "py.h5"), tmp_path / "ref.h5")


def test_gsa_report(sobol_pair, tmp_path):
    sobol_pair[0].report(tmp_path / "g.html")
    html = (tmp_path / "g.html").read_text()
    assert "<html" in html.lower() and "S1" in html


@pytest.mark.parametrize("replace", [{"N = 8192": "N = 1"}, {'features = ["y"]': 'features = ["yy"]'},
                                     {"second_order = true": "levels = 4"}])
def test_gsa_errors_have_cli_message(tmp_path, replace):
    path, _ = ishigami(tmp_path, **replace)
    with pytest.raises(phasmid.ConfigError) as e:
        phasmid.gsa(path)
    assert str(e.value) == cli_error("gsa", path, "-q", "-o", str(tmp_path / "x.h5"))
    assert "gsa.toml:" in str(e.value) and "[gsa" in str(e.value)


INTERRUPTED = r"""
import sys, phasmid
from conftest import print_running_when_guarded
print_running_when_guarded()
try:
    phasmid.gsa(sys.argv[1], threads=1)
except KeyboardInterrupt as e:
    print("interrupted: %s" % e, flush=True)
"""


def test_ctrl_c_interrupts_a_gsa():
    # The shipped config's N (D + 2) runs of its t_end_ms on one thread, all of them still to
    # come when the sweep engine installs its SIGINT handler (the sign the child prints
    # "running" on, within a millisecond): SIGINT then ends the analysis with most not done.
    path = config("gsa_single_joint.toml")
    with open(path, "rb") as f:
        toml = tomllib.load(f)
    assert toml["gsa"]["second_order"] is False
    n_points = toml["gsa"]["N"] * (len(toml["sweep"]["parameter"]) + 2)
    child = Child(INTERRUPTED, path)
    child.wait_for_line("running")
    child.p.send_signal(signal.SIGINT)
    rc, out, err = child.finish()
    assert rc == 0, err
    m = re.search(r"interrupted: gsa interrupted with (\d+) of (\d+) points done", out)
    assert m and int(m.group(2)) == n_points and int(m.group(1)) < n_points, out + err
