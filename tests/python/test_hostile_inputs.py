"""Hostile inputs to the Python module (issue #42, docs/python.md "Errors" and "Outputs"): every
output goes through the CLI's output-path check with the files the result came from, read()
takes only regular files in one bounded step, every keyword goes through the config's own
checks, and every refusal is a phasmid exception whose one-line message names the parameter or
the file. Each refusal also asserts that nothing was written: no new file, no .tmp, and the
config's bytes unchanged."""
import os
import stat

import h5py
import pytest

import phasmid
from conftest import Child, cli, config
from test_errors import cli_error

# A fast analytic model: a [sweep] grid of 27 points, and (other file) a small [gsa] design.
ISHIGAMI = """[model]
type = "ishigami"
[parameters]
a = 7.0
b = 0.1
[[sweep.parameter]]
name = "x1"
lower = -3.0
upper = 3.0
%(points)s
[[sweep.parameter]]
name = "x2"
lower = -3.0
upper = 3.0
%(points)s
[[sweep.parameter]]
name = "x3"
lower = -3.0
upper = 3.0
%(points)s
"""
GRID = ISHIGAMI % {"points": "points = 3"} + '[sweep]\ndesign = "grid"\n'
GSA = ISHIGAMI % {"points": ""} + """[gsa]
method = "sobol"
N = 16
second_order = false
bootstrap = 10
seed = 1
features = ["y"]
"""
SHORT = dict(t_end_ms=200, discard_ms=0)  # a short run of the single joint


def listing(d):
    """Every name in a directory tree (to see that a refused call created nothing)."""
    return sorted(os.path.relpath(os.path.join(r, n), d) for r, ds, fs in os.walk(d) for n in ds + fs)


class Unchanged:
    """Asserts on exit that a directory holds the same names and `files` the same bytes."""

    def __init__(self, d, *files):
        self.d, self.files = str(d), [str(f) for f in files]

    def __enter__(self):
        self.names = listing(self.d)
        self.bytes = [open(f, "rb").read() for f in self.files]
        return self

    def __exit__(self, *exc):
        assert listing(self.d) == self.names, "a refused call left files behind"
        assert [open(f, "rb").read() for f in self.files] == self.bytes, "a refused call changed an input"


def one_line(e, *names):
    """The exception's message is one line naming every one of `names`."""
    text = str(e.value)
    assert "\n" not in text and text, text
    for n in names:
        assert str(n) in text, "%r does not name %r" % (text, n)
    return text


@pytest.fixture
def fti(tmp_path):
    """The shipped single-joint config as a file of its own, its scenario and a short run."""
    path = tmp_path / "c.toml"
    path.write_text(open(config("single_joint_fti.toml")).read())
    s = phasmid.load(path)
    return path, s, s.simulate(**SHORT)


class Isl:
    """The Ishigami configs (sweep: its [sweep] grid; gsa: its [gsa]) and their results."""


@pytest.fixture(scope="module")
def isl(tmp_path_factory):
    d = tmp_path_factory.mktemp("isl")
    i = Isl()
    i.dir, i.sweep_cfg, i.gsa_cfg = d, d / "grid.toml", d / "gsa.toml"
    i.sweep_cfg.write_text(GRID)
    i.gsa_cfg.write_text(GSA)
    i.sweep, i.gsa = phasmid.sweep(i.sweep_cfg, threads=1), phasmid.gsa(i.gsa_cfg, threads=1)
    i.cfg = {"sweep": i.sweep_cfg, "gsa": i.gsa_cfg}
    return i


@pytest.fixture(scope="module")
def fit_file(tmp_path_factory, binary):
    """A fit file written by the CLI (read() gives its FitResult)."""
    d = tmp_path_factory.mktemp("fit")
    out = d / "fit.h5"
    cli("fit", config("fit_fti_section31.toml"), "-q", "-j", "1", "--multistart", "1", "-o", str(out))
    return out


# --- Outputs: the CLI's output-path check, with the result's inputs ---------------------------

def test_simulation_save_over_its_config_is_refused(fti, tmp_path):
    path, _, run = fti
    with Unchanged(tmp_path, path), pytest.raises(phasmid.Error) as e:
        run.save(path)
    assert "is the input" in one_line(e, path)


def test_simulation_report_over_its_config_is_refused(fti, tmp_path):
    path, _, run = fti
    with Unchanged(tmp_path, path), pytest.raises(phasmid.Error) as e:
        run.report(str(path))
    one_line(e, path)


def test_the_config_by_another_name_is_refused(fti, tmp_path, monkeypatch):
    # Compared by device and inode: "./c.toml" and a hard link are the config too.
    path, _, run = fti
    os.link(path, tmp_path / "link.toml")
    monkeypatch.chdir(tmp_path)
    for name in ("./c.toml", "link.toml"):
        with Unchanged(tmp_path, path), pytest.raises(phasmid.Error) as e:
            run.save(name)
        one_line(e, name)


def test_sensitivity_save_over_its_config_is_refused(fti, tmp_path):
    path, s, _ = fti
    sens = s.sensitivity(parameters=["middle.fti.b_v"], **SHORT)
    with Unchanged(tmp_path, path), pytest.raises(phasmid.Error) as e:
        sens.save(path)
    one_line(e, path)


@pytest.mark.parametrize("kind", ["sweep", "gsa"])
def test_sweep_and_gsa_save_and_report_over_their_config_are_refused(isl, kind):
    path, result = isl.cfg[kind], getattr(isl, kind)
    for write in (result.save, result.report):
        with Unchanged(path.parent, path), pytest.raises(phasmid.Error) as e:
            write(path)
        assert "is the input" in one_line(e, path)


def test_read_result_save_over_the_file_read_is_refused(isl, tmp_path):
    f = isl.sweep.save(tmp_path / "s.h5")
    back = phasmid.read(f)
    with Unchanged(tmp_path, f), pytest.raises(phasmid.Error) as e:
        back.save(f)
    one_line(e, f)


@pytest.mark.parametrize("kind", ["sweep", "gsa", "fit", "read", "simulate"])
def test_save_through_a_symlink_to_dev_null_is_refused(isl, fit_file, fti, tmp_path, kind):
    result = {"sweep": isl.sweep, "gsa": isl.gsa, "fit": phasmid.read(fit_file), "read": phasmid.read(fit_file),
              "simulate": fti[2]}[kind]
    link = tmp_path / "out.h5"
    os.symlink("/dev/null", link)
    with Unchanged(tmp_path), pytest.raises(phasmid.Error) as e:
        result.save(link)
    assert "character device" in one_line(e, link)


@pytest.mark.parametrize("kind", ["sweep", "read", "simulate"])
def test_a_directory_as_target_is_a_phasmid_error(isl, fit_file, fti, tmp_path, kind):
    result = {"sweep": isl.sweep, "read": phasmid.read(fit_file), "simulate": fti[2]}[kind]
    (tmp_path / "d").mkdir()
    for write in (result.save, result.report):
        with Unchanged(tmp_path), pytest.raises(phasmid.Error) as e:
            write(tmp_path / "d")
        assert not isinstance(e.value, IsADirectoryError)
        assert "a directory" in one_line(e, tmp_path / "d")


def test_a_directory_in_place_of_the_tmp_companion_is_refused(isl, tmp_path):
    (tmp_path / "x.h5.tmp").mkdir()
    with Unchanged(tmp_path), pytest.raises(phasmid.Error) as e:
        isl.sweep.save(tmp_path / "x.h5")
    one_line(e, "x.h5.tmp")


def test_save_to_a_fifo_is_refused_without_blocking(isl, tmp_path):
    os.mkfifo(tmp_path / "f.h5")
    with Unchanged(tmp_path), pytest.raises(phasmid.Error) as e:
        isl.gsa.save(tmp_path / "f.h5")
    assert "a fifo" in one_line(e, "f.h5")


def test_save_into_a_missing_directory_creates_it_as_the_cli_does(isl, tmp_path):
    isl.sweep.save(tmp_path / "no" / "x.h5")
    assert listing(tmp_path) == ["no", "no/x.h5"]


def test_save_below_a_regular_file_names_the_path(isl, tmp_path):
    (tmp_path / "f").write_bytes(b"a file, not a directory")
    with Unchanged(tmp_path), pytest.raises(phasmid.Error) as e:
        isl.sweep.save(tmp_path / "f" / "x.h5")
    one_line(e, tmp_path / "f" / "x.h5")


def test_a_good_save_replaces_a_regular_file_and_leaves_no_tmp(isl, tmp_path):
    out = tmp_path / "s.h5"
    out.write_bytes(b"old")
    isl.sweep.save(out)
    assert listing(tmp_path) == ["s.h5"] and phasmid.read(out).points.shape == (27, 3)


def test_save_path_of_a_wrong_type(isl):
    with pytest.raises(phasmid.Error) as e:
        isl.sweep.save(3)
    one_line(e, "path", "3")


# --- read(): regular files only, one bounded read, errors naming the file ------------------

def test_read_of_dev_zero_is_refused_before_reading():
    with pytest.raises(phasmid.Error) as e:
        phasmid.read("/dev/zero")
    assert "character device" in one_line(e, "/dev/zero")


def test_read_of_a_fifo_does_not_block(tmp_path):
    fifo = tmp_path / "f.h5"
    os.mkfifo(fifo)
    child = Child("import sys, phasmid\ntry:\n    phasmid.read(sys.argv[1])\nexcept phasmid.Error as e:\n"
                  "    print('refused: %s' % e)\n", str(fifo))
    rc, out, err = child.finish()  # fails (does not hang) after conftest.HANG_SECONDS
    assert rc == 0 and out.startswith("refused: %s: " % fifo) and "a fifo" in out, out + err


@pytest.mark.parametrize("content", ["dir", "text", "truncated", "empty", "missing"])
def test_read_of_what_is_not_a_phasmid_file_names_it(isl, tmp_path, content):
    path = tmp_path / "x.h5"
    if content == "dir":
        path.mkdir()
    elif content == "text":
        path.write_text("time_ms,middle.fti\n0,1\n")
    elif content == "truncated":
        good = open(isl.sweep.save(tmp_path / "good.h5"), "rb").read()
        path.write_bytes(good[: len(good) // 2])
    elif content == "empty":
        path.write_bytes(b"")
    with pytest.raises(phasmid.Error) as e:
        phasmid.read(path)
    assert not isinstance(e.value, (OSError, RuntimeError))
    assert one_line(e).startswith(str(path) + ":")


def test_read_of_an_incomplete_fit_file_names_it(tmp_path):
    path = tmp_path / "f.h5"
    with h5py.File(path, "w") as f:
        f["fit/parameter_names"] = [b"a"]
    with pytest.raises(phasmid.Error) as e:
        phasmid.read(path)
    assert "not a complete phasmid file" in one_line(e, path)


# --- simulate(): the config's [simulation] checks and the run-size bound ----------------------

@pytest.mark.parametrize("key,value,says", [
    ("t_end_ms", 2e7, "t_end_ms = 20000000 must be in (0, 10000000] ms"),
    ("output_dt_ms", 1e-4, "output_dt_ms = 0.0001 must be in [0.001, t_end_ms] ms"),
    ("rtol", -1, "'rtol' must be > 0"),
    ("rtol", 0, "'rtol' must be > 0"),
    ("rtol", 1, "'rtol' must be < 1"),
    ("atol", 0, "'atol' must be > 0"),
    ("max_step_ms", -1, "'max_step_ms' must be > 0"),
    ("discard_ms", 9000, "discard_ms = 9000 must be in [0, t_end_ms = 9000)"),
    ("discard_ms", -1, "discard_ms = -1 must be in [0, t_end_ms = 9000)"),
])
def test_simulate_refuses_what_the_config_refuses(key, value, says):
    s = phasmid.load(config("single_joint_fti.toml"))
    with pytest.raises(phasmid.ConfigError) as e:
        s.simulate(**{key: value})
    text = one_line(e, key, says)
    assert text.startswith("simulate(): ")


def test_simulate_message_is_the_configs_own(tmp_path, binary):
    # The same key in [simulation] gives the CLI's message with file:line in place of "simulate()".
    bad = tmp_path / "bad.toml"
    bad.write_text(open(config("single_joint_fti.toml")).read().replace("[simulation]\n", "[simulation]\nrtol = -1.0\n"))
    expected = cli_error("simulate", str(bad), "-o", str(tmp_path / "x.h5"))
    with pytest.raises(phasmid.ConfigError) as e:
        phasmid.load(config("single_joint_fti.toml")).simulate(rtol=-1)
    assert expected.split(": ", 1)[1] == str(e.value).split(": ", 1)[1]


@pytest.mark.parametrize("value", ["text", None, 10 ** 400, float("nan"), float("inf"), True, [1.0]])
def test_simulate_keyword_of_a_wrong_type_names_it(value):
    with pytest.raises(phasmid.ConfigError) as e:
        phasmid.load(config("single_joint_fti.toml")).simulate(rtol=value)
    one_line(e, "simulate()", "'rtol'")


@pytest.mark.parametrize("value", [0, -3, 2.5, 1e12])
def test_simulate_max_steps_must_be_a_positive_integer(value):
    with pytest.raises(phasmid.ConfigError) as e:
        phasmid.load(config("single_joint_fti.toml")).simulate(max_steps=value, **SHORT)
    one_line(e, "'max_steps'")


# --- sensitivity(): the [sensitivity] parser's checks ---------------------------------------

@pytest.mark.parametrize("kw,names", [
    (dict(parameters=[]), ["parameters", "empty"]),
    (dict(parameters="middle.fti.b_v"), ["'parameters'", "list of names"]),
    (dict(parameters=["middle.fti.b_v", 3]), ["'parameters'", "3"]),
    (dict(t_end_ms=2e7), ["t_end_ms", "10000000"]),
    (dict(t_end_ms=200), ["discard_ms = 2000"]),
    (dict(method="nope"), ["nope"]),
    (dict(trajectory="yes"), ["'trajectory'"]),
])
def test_sensitivity_refuses_with_the_keyword_named(kw, names):
    s = phasmid.load(config("single_joint_fti.toml"))
    with pytest.raises(phasmid.ConfigError) as e:
        s.sensitivity(**kw)
    one_line(e, "sensitivity()", *names)


def test_an_empty_parameter_list_in_the_config_is_refused_too(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(open(config("single_joint_fti.toml")).read() + "\n[sensitivity]\nparameters = []\n")
    with pytest.raises(phasmid.ConfigError) as e:
        phasmid.load(path).sensitivity()
    one_line(e, "s.toml:", "parameters is empty")


# --- fit(): the CLI's option checks, in the one place both reach ---------------------------

@pytest.mark.parametrize("kw,option", [
    (dict(multistart=-1), "--multistart -1"), (dict(multistart=0), "--multistart 0"),
    (dict(max_iterations=-1), "--max-iterations -1"), (dict(seed=-2), "--seed -2"),
    (dict(threads=-1), "-j/--threads -1"), (dict(threads=10 ** 6), "-j/--threads"),
    (dict(max_iterations=2 ** 40), "--max-iterations"),
])
def test_fit_option_out_of_range_is_refused_as_the_cli_refuses_it(kw, option):
    with pytest.raises(phasmid.ConfigError) as e:
        phasmid.fit(config("fit_fti_section31.toml"), **kw)
    one_line(e, option)


@pytest.mark.parametrize("kw,key", [(dict(multistart=2.5), "multistart"), (dict(seed="1"), "seed"),
                                    (dict(max_iterations=10 ** 400), "max_iterations"), (dict(data=3), "data"),
                                    (dict(profile="middle.fti.b_v"), "profile")])
def test_fit_option_of_a_wrong_type_names_it(kw, key):
    with pytest.raises(phasmid.ConfigError) as e:
        phasmid.fit(config("fit_fti_section31.toml"), **kw)
    one_line(e, "'%s'" % key)


@pytest.mark.parametrize("args,says", [(["--multistart", "-1"], "--multistart -1: must be an integer >= 1"),
                                       (["--max-iterations", "-1"], "--max-iterations -1: must be an integer >= 1")])
def test_cli_fit_refuses_negative_counts_too(tmp_path, binary, args, says):
    with Unchanged(tmp_path):
        assert cli_error("fit", config("fit_fti_section31.toml"), *args, "-o", str(tmp_path / "f.h5")) == says


# --- sweep() and gsa(): threads, out=, resume= and the message of an unfinished run ---------

@pytest.mark.parametrize("threads", [-3, 10 ** 30, 2.0, "2", None])
@pytest.mark.parametrize("run", ["sweep", "gsa"])
def test_sweep_and_gsa_threads_are_checked(isl, run, threads):
    with Unchanged(isl.dir), pytest.raises(phasmid.ConfigError) as e:
        getattr(phasmid, run)(isl.cfg[run], threads=threads)
    one_line(e, "threads")


def test_resume_needs_out(isl):
    with pytest.raises(phasmid.ConfigError) as e:
        phasmid.sweep(isl.sweep_cfg, resume=True)
    one_line(e, "resume=True", "out=")


@pytest.mark.parametrize("run", ["sweep", "gsa"])
def test_out_is_checked_like_the_clis_output(isl, tmp_path, run):
    (tmp_path / "d").mkdir()
    os.symlink("/dev/null", tmp_path / "null.h5")
    cfg = isl.cfg[run]
    for out in (cfg, tmp_path / "d", tmp_path / "null.h5"):
        with Unchanged(isl.dir, cfg), Unchanged(tmp_path), pytest.raises(phasmid.Error) as e:
            getattr(phasmid, run)(cfg, threads=1, out=out)
        one_line(e, out)


def test_an_unfinished_sweep_says_where_its_points_are_and_resume_continues(isl, tmp_path):
    out = tmp_path / "s.h5"
    with pytest.raises(phasmid.Error) as e:
        phasmid.sweep(isl.sweep_cfg, threads=1, out=out, _stop_after=5)
    text = one_line(e, "sweep stopped with 5 of 27 points done", "%s.journal" % out, "resume=True")
    assert os.path.exists("%s.journal" % out) and not os.path.exists(out), text
    done = phasmid.sweep(isl.sweep_cfg, threads=1, out=out, resume=True)
    assert done.outcome["n_recovered"] == 5 and done.points.shape == (27, 3)
    assert listing(tmp_path) == ["s.h5"]
    assert (done.data["/sweep/features/y"] == isl.sweep.data["/sweep/features/y"]).all()


def test_an_unfinished_sweep_without_out_says_nothing_is_kept(isl):
    with pytest.raises(phasmid.Error) as e:
        phasmid.sweep(isl.sweep_cfg, threads=1, _stop_after=2)
    assert "nothing kept" in one_line(e, "sweep stopped with 2 of 27 points done")
    assert ".journal (" not in str(e.value) and "phasmid-" not in str(e.value)


def test_gsa_into_out_equals_the_temporary_run(isl, tmp_path):
    g = phasmid.gsa(isl.gsa_cfg, threads=1, out=tmp_path / "g.h5")
    assert listing(tmp_path) == ["g.h5"]
    assert (g.features["y"].S1 == isl.gsa.features["y"].S1).all()


# --- set=, load(): overrides and paths of a wrong type, named ------------------------------

@pytest.mark.parametrize("sets,names", [
    ({"middle.fti.b_v": "text"}, ["middle.fti.b_v", "'text'"]),
    ({"middle.fti.b_v": None}, ["middle.fti.b_v", "None"]),
    ({"middle.fti.b_v": 10 ** 400}, ["middle.fti.b_v", "range of a double"]),
    ({"middle.fti.b_v": float("nan")}, ["middle.fti.b_v", "finite"]),
    ("middle.fti.b_v=3", ["set", "'middle.fti.b_v=3'"]),
    ([3.0], ["set", "3.0"]),
    ({3: 1.0}, ["set", "3"]),
    (5, ["set", "5"]),
])
def test_set_of_a_wrong_type_names_the_parameter(fti, sets, names):
    path = fti[0]
    with pytest.raises(phasmid.ConfigError) as e:
        phasmid.load(path, set=sets)
    one_line(e, *names)
    with pytest.raises(phasmid.ConfigError):
        phasmid.sweep(path, set=sets)


def test_with_parameters_of_a_wrong_type_names_it(fti):
    with pytest.raises(phasmid.ConfigError) as e:
        fti[1].with_parameters("middle.fti.b_v=3")
    one_line(e, "with_parameters()")


@pytest.mark.parametrize("path", [None, 3, b"c.toml", "", "c\0.toml"])
def test_load_read_and_save_of_a_path_of_a_wrong_type(isl, tmp_path, path):
    for call in (phasmid.load, phasmid.read, isl.sweep.save, isl.sweep.report):
        with Unchanged(tmp_path), pytest.raises(phasmid.Error) as e:
            call(path)
        one_line(e, "path")


def test_an_unfinished_gsa_into_out_resumes_to_the_same_indices(isl, tmp_path):
    out = tmp_path / "g.h5"
    with pytest.raises(phasmid.Error) as e:
        phasmid.gsa(isl.gsa_cfg, threads=1, out=out, _stop_after=3)
    one_line(e, "gsa stopped with 3 of", "%s.journal" % out, 'phasmid.gsa(..., out="%s", resume=True)' % out)
    g = phasmid.gsa(isl.gsa_cfg, threads=1, out=out, resume=True)
    assert g.outcome["n_recovered"] == 3 and listing(tmp_path) == ["g.h5"]
    assert (g.features["y"].S1 == isl.gsa.features["y"].S1).all()


INTERRUPTED_INTO_OUT = r"""
import sys, phasmid
from conftest import print_running_when_guarded
print_running_when_guarded()
try:
    phasmid.gsa(sys.argv[1], threads=1, out=sys.argv[2])
except KeyboardInterrupt as e:
    print("interrupted: %s" % e, flush=True)
"""


def test_ctrl_c_of_a_gsa_into_out_names_its_journal_and_the_call_that_resumes(tmp_path):
    # As test_gsa.test_ctrl_c_interrupts_a_gsa: SIGINT once the sweep engine's handler is in
    # place (the child's "running"), with most of the shipped config's points still to come.
    import signal
    out = tmp_path / "g.h5"
    child = Child(INTERRUPTED_INTO_OUT, config("gsa_single_joint.toml"), str(out))
    child.wait_for_line("running")
    child.p.send_signal(signal.SIGINT)
    rc, text, err = child.finish()
    assert rc == 0, err
    assert "interrupted: gsa interrupted with " in text, text + err
    assert "kept in %s.journal" % out in text and 'phasmid.gsa(..., out="%s", resume=True)' % out in text, text
    assert listing(tmp_path) == ["g.h5.journal"]


def test_fit_result_save_over_its_data_or_parameter_table_is_refused(tmp_path):
    # A copy of the shipped kinematic fit with its recording and parameter table next to it.
    src = os.path.join(os.path.dirname(config("x")), "..", "datasets", "synthetic")
    (tmp_path / "datasets" / "synthetic").mkdir(parents=True)
    (tmp_path / "configs").mkdir()
    for name in ("fti_kinematics_synthetic.csv", "fti_kinematics_params.tsv"):
        (tmp_path / "datasets" / "synthetic" / name).write_bytes(open(os.path.join(src, name), "rb").read())
    cfg = tmp_path / "configs" / "fit.toml"
    cfg.write_text(open(config("fit_fti_kinematic_synthetic.toml")).read())
    fit = phasmid.fit(cfg, threads=1, max_iterations=2)
    data = tmp_path / "datasets" / "synthetic" / "fti_kinematics_synthetic.csv"
    table = tmp_path / "datasets" / "synthetic" / "fti_kinematics_params.tsv"
    for target in (cfg, data, table):
        with Unchanged(tmp_path, cfg, data, table), pytest.raises(phasmid.Error) as e:
            fit.save(target)
        assert "is the input" in one_line(e, target.name)
