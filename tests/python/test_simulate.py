"""Scenario.simulate against `phasmid simulate`: the same arrays bit for bit, handed to NumPy
without copying; parameters and overrides (docs/python.md)."""
import numpy as np
import pytest

import phasmid
from conftest import assert_same_bits, cli, config, h5_datasets

SET = {"middle.fti.b_v": 13.0}


@pytest.fixture(scope="module")
def run():
    return phasmid.load(config("single_joint_fti.toml"), set=SET).simulate(t_end_ms=3000)


@pytest.fixture(scope="module")
def reference(tmp_path_factory, binary):
    # The same run by the CLI: t_end_ms through the config text, b_v through --set.
    d = tmp_path_factory.mktemp("sim")
    text = open(config("single_joint_fti.toml")).read().replace("t_end_ms = 9000", "t_end_ms = 3000")
    assert "t_end_ms = 3000" in text
    (d / "sj.toml").write_text(text)
    cli("simulate", str(d / "sj.toml"), "--set", "middle.fti.b_v=13", "-q", "-o", str(d / "ref.h5"))
    return h5_datasets(d / "ref.h5")


def test_arrays_equal_cli_file_bit_for_bit(run, reference):
    assert_same_bits(run.time, reference["/trajectory/time"], "time")
    assert len(run.time) == 3001 and run.time[-1] == 3000.0
    assert_same_bits(run.angles["middle"]["fti"], reference["/trajectory/angles/middle/fti"], "angle")
    assert_same_bits(run.angular_velocity["middle"]["fti"], reference["/trajectory/angular_velocity/middle/fti"])
    states = {k[len("/trajectory/states/"):]: v for k, v in reference.items() if k.startswith("/trajectory/states/")}
    assert sorted(states) == sorted(run.states) and len(states) == run.y.shape[1] > 10
    for name, arr in states.items():
        assert_same_bits(run.states[name], arr, name)
    feats = {k[len("/features/"):]: v for k, v in reference.items() if k.startswith("/features/")}
    assert sorted(feats) == sorted(run.features) and "period_ms" in feats
    for name, value in feats.items():
        assert_same_bits(run.features[name], np.asarray(value).reshape(-1)[0], name)
    assert run.features.units["period_ms"] == "ms" and run.features.units["middle.fti.angle_min_deg"] == "deg"
    assert_same_bits(reference["/parameters/values"], phasmid.load(config("single_joint_fti.toml"), set=SET).parameters.values)


def test_save_writes_the_cli_file(run, reference, tmp_path):
    saved = h5_datasets(run.save(tmp_path / "py.h5"))
    assert sorted(saved) == sorted(reference)
    for k in reference:
        assert_same_bits(saved[k], reference[k], k)
    back = phasmid.read(tmp_path / "py.h5")
    assert isinstance(back, phasmid.SimulationResult) and back.model == "single_joint"
    assert_same_bits(back.angles["middle"]["fti"], run.angles["middle"]["fti"])
    assert back.features == run.features


def test_arrays_are_views_of_the_cpp_result(run):
    for arr in (run.time, run.y, run.angles["middle"]["fti"]):
        assert arr.flags.owndata is False and arr.flags.writeable is False
        assert type(arr.base).__name__ in ("Simulation",)
    assert run.time.base is run.y.base  # both views of one C++ result object
    state = run.states["middle.fti.gamma"]
    assert np.shares_memory(state, run.y) and state.base is run.y  # a strided column of y
    assert np.shares_memory(run.angles["middle"]["fti"], run.angles["middle"]["fti"][10:])
    with pytest.raises(ValueError):
        run.time[0] = 1.0


def test_events_are_the_turning_points(run):
    # Every angular-velocity root of the angle is a turning point: the angle's extrema.
    ev = [e for e in run.events if e.state == "middle.fti.gamma_dot"]
    assert len(ev) >= 4 and all(e.direction in (-1, 1) for e in ev)
    t = np.array([e.t_ms for e in ev])
    maxima = t[[e.direction == -1 for e in ev]]
    angle = run.angles["middle"]["fti"]
    for tm in maxima[maxima > 1000]:
        k = int(round(tm))
        assert angle[k] >= angle[k - 5] and angle[k] >= angle[k + 5]


def test_parameters_and_with_parameters():
    s = phasmid.load(config("single_joint_fti.toml"))
    p = s.parameters["middle.fti.b_v"]
    assert p.unit and p.source and p.lower <= p.value <= p.upper
    assert len(s.parameters) == len(s.parameters.names) > 20
    s2 = s.with_parameters({"middle.fti.b_v": 2 * p.value})
    assert s2.parameters["middle.fti.b_v"].value == 2 * p.value
    assert s.parameters["middle.fti.b_v"].value == p.value  # never in place
    assert "middle.fti.b_v=" in s2.config_text


def test_loads_from_text_equals_load():
    text = open(config("single_joint_fti.toml")).read()
    a = phasmid.loads(text).simulate(t_end_ms=500, discard_ms=0)
    b = phasmid.load(config("single_joint_fti.toml")).simulate(t_end_ms=500, discard_ms=0)
    assert_same_bits(a.y, b.y)


def test_non_ode_kind_carries_its_file(tmp_path):
    run = phasmid.load(config("cruse1980_gait2.toml")).simulate()
    assert run.time is not None and len(run.time) > 10
    assert "position" in " ".join(run.data) and run.features
    assert "cruse1980" in repr(phasmid.read(run.save(tmp_path / "c.h5")).model)
