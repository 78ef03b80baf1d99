"""Errors raise phasmid exceptions carrying the CLI's one-line messages (docs/python.md)."""
import pytest

import phasmid
from conftest import cli, config


def cli_error(*args):
    r = cli(*args, check=False)
    assert r.returncode == 1
    line = r.stderr.strip().splitlines()[-1]
    assert line.startswith("phasmid: error: ")
    return line[len("phasmid: error: "):]


def test_exception_hierarchy():
    assert issubclass(phasmid.ConfigError, phasmid.Error)
    assert issubclass(phasmid.SolverError, phasmid.Error)
    assert issubclass(phasmid.Error, Exception)


def test_missing_file_is_config_error_with_cli_message(tmp_path):
    missing = str(tmp_path / "nope.toml")
    with pytest.raises(phasmid.ConfigError) as e:
        phasmid.load(missing)
    assert str(e.value) == cli_error("simulate", missing, "-o", str(tmp_path / "x.h5"))
    assert "nope.toml" in str(e.value) and "\n" not in str(e.value)


def test_bad_toml_names_file_and_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[model]\ntype = "single_joint"\nleg = "middle"\njoint = "fti"\n[simulation]\nt_end_msx = 3\n')
    with pytest.raises(phasmid.ConfigError) as e:
        phasmid.load(str(bad))
    assert str(e.value) == cli_error("simulate", str(bad), "-o", str(tmp_path / "x.h5"))
    assert "bad.toml:6" in str(e.value)


def test_unknown_parameter_override_has_cli_message(tmp_path):
    with pytest.raises(phasmid.ConfigError) as e:
        phasmid.load(config("single_joint_fti.toml"), set={"middle.fti.b_vv": 1.0})
    expected = cli_error("simulate", config("single_joint_fti.toml"), "--set", "middle.fti.b_vv=1.0", "-o",
                         str(tmp_path / "x.h5"))
    assert str(e.value) == expected and "middle.fti.b_vv" in expected


def test_value_outside_admissible_range(tmp_path):
    s = phasmid.load(config("single_joint_fti.toml"))
    with pytest.raises(phasmid.ConfigError) as e:
        s.with_parameters({"middle.fti.b_v": -5.0})
    assert str(e.value) == cli_error("simulate", config("single_joint_fti.toml"), "--set", "middle.fti.b_v=-5.0",
                                     "-o", str(tmp_path / "x.h5"))


def test_unknown_options_and_parameters():
    s = phasmid.load(config("single_joint_fti.toml"))
    with pytest.raises(phasmid.ConfigError, match="unknown option 'tend'"):
        s.simulate(tend=5)
    with pytest.raises(phasmid.ConfigError, match="middle.fti.nothing"):
        s.sensitivity(parameters=["middle.fti.nothing"])
    with pytest.raises(phasmid.ConfigError, match="unknown option 'iterations'"):
        phasmid.fit(config("fit_fti_section31.toml"), iterations=3)


def test_solver_failure_is_solver_error():
    # Two steps per output interval are far too few for the CPG's spikes: CVODES gives up.
    with pytest.raises(phasmid.SolverError) as e:
        phasmid.load(config("single_joint_fti.toml")).simulate(t_end_ms=1000, discard_ms=0, max_steps=2)
    assert "\n" not in str(e.value) and str(e.value)


def test_read_refuses_a_declared_extent_the_file_cannot_hold(tmp_path):
    # 6e8 unallocated doubles (4.8 GB) declared in a file of a few kB: refused before reading.
    import h5py
    path = str(tmp_path / "huge.h5")
    with h5py.File(path, "w") as f:
        f.create_dataset("trajectory/time", shape=(600000000,), dtype="f8", chunks=(1000,))
    with pytest.raises(phasmid.Error) as e:
        phasmid.read(path)
    assert str(e.value).startswith(path + ": dataset /trajectory/time declares 600000000 values")
