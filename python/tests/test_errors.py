"""Errors from Python: a broken model is a ModelError with file, line and column; a failed
run a RunError with its time and state; a bad argument a ValueError or TypeError naming it.
Never a panic across the boundary."""

import math

import pytest

import varmass
from conftest import MODELS, SLED

BROKEN = """coordinates x
mass m = m0 + c*x
body sled: mass mm, position [x]
"""


def test_a_broken_model_file_is_a_model_error_with_file_line_and_column(tmp_path):
    path = tmp_path / "broken.vms"
    path.write_text(BROKEN)
    with pytest.raises(varmass.ModelError) as caught:
        varmass.Model.from_file(path)
    error = caught.value
    # `mm` starts at column 17 of line 3 (1-based), as `varmass check` points at it.
    assert (error.file, error.line, error.column) == (str(path), 3, 17)
    assert error.message == "`mm` is not a declared mass"
    assert str(error).startswith("error: `mm` is not a declared mass\n --> ")
    assert "body sled: mass mm, position [x]" in str(error)


def test_a_model_error_lists_every_diagnostic():
    text = "coordinates x\nmass m = m0\nbody b: mass m, position [x]\npotential m*g*x +\n"
    with pytest.raises(varmass.ModelError) as caught:
        varmass.Model(text)
    error = caught.value
    assert error.file == "<model>" and error.line == 4
    assert len(error.diagnostics) >= 1 and error.diagnostics[0].line == 4


def test_a_failing_check_is_a_model_error_at_the_check():
    text = (MODELS / "sled.vms").read_text() + "check p_x = 2*m*x'\n"
    with pytest.raises(varmass.ModelError) as caught:
        varmass.Model(text, with_=["impact"], name="sled+.vms")
    last_line = text.count("\n")
    assert (caught.value.file, caught.value.line, caught.value.column) == ("sled+.vms", last_line, 1)


def test_a_failed_run_is_a_run_error_with_its_time_and_state(rocket):
    # m = 100 − 10 t reaches 0 at t = 10: the run fails there with the mass not positive.
    with pytest.raises(varmass.RunError) as caught:
        rocket.run(set={"mu": 10, "u_e": 2500, "g": 9.81}, init={"y": 0, "m": 100}, until=100)
    error = caught.value
    assert error.reason == "the mass `m` is not positive"
    assert abs(error.time - 10.0) < 1e-9, error.time
    assert set(error.state) == {"y", "y'", "p_y", "m"}
    assert abs(error.state["m"]) < 1e-9
    # Before the failure the rocket climbed: v = u_e ln(m0/m) − g t grows without bound as
    # m → 0, so y is well above 0 there.
    assert error.state["y"] > 1e4
    # The points recorded before the failure come with it: m = 100 − 10 t is integrated
    # exactly up to rounding (a linear law), every kept m is positive, the last just before
    # the burn-out at t = 10 (rounding may put it a few ulps past).
    points = error.points
    assert set(points) == {"t", "y", "y'", "m"}, set(points)
    assert len(points["t"]) > 10
    assert (points["m"] > 0).all()
    assert abs(points["m"] - (100 - 10 * points["t"])).max() < 1e-10
    assert 9.9 < points["t"][-1] < 10 + 1e-12
    assert str(error).startswith("the run failed at t = ")


def run_sled(sled, **overrides):
    arguments = dict(set=SLED, init={"x": 0}, until=10.0)
    arguments.update(overrides)
    return sled.run(**arguments)


SET_WITHOUT_F_D = {k: v for k, v in SLED.items() if k != "f_d"}

BAD_RUNS = [
    # (arguments, exception, text the message must contain: the argument's name)
    (dict(until="10"), TypeError, "until"),
    (dict(until=math.nan), ValueError, "until"),
    (dict(until=None), TypeError, "until"),
    (dict(set=[1, 2]), TypeError, "set"),
    (dict(set={**SLED, "m0": "ten"}), TypeError, "set['m0']"),
    (dict(set={**SLED, "zz": 1.0}), ValueError, "`zz` is not a parameter"),
    (dict(set=SET_WITHOUT_F_D), ValueError, "missing value for f_d"),
    # Python's words, not the command line's (before: "give --set f_d=VALUE").
    (dict(set=SET_WITHOUT_F_D), ValueError, 'give `set={"f_d": VALUE}`'),
    (dict(init={"y": 0}), ValueError, "`y` is not a coordinate"),
    (dict(init={"x": math.inf}), ValueError, "init['x']"),
    (dict(tol=-1e-9), ValueError, "tol"),
    (dict(tol=1e-9, step=0.1), ValueError, "tol and step"),
    # Below the method's floor (core/src/tolerance.rs `Floor`), named with it.
    (dict(tol=1e-15), ValueError, 'finer than "dormand-prince" can honour (its floor is 2.220446049250313e-14'),
    (dict(tol=5e-16, method="taylor"), ValueError, 'finer than "taylor" can honour (its floor is 1e-15'),
    (dict(step="0.1"), TypeError, "step"),
    (dict(method="rk5"), ValueError, "method 'rk5'"),
    (dict(method=4), TypeError, "method"),
    (dict(method="rk4"), ValueError, '`method="rk4"` takes a fixed step: give `step=H`'),
    (dict(record=["xx"]), ValueError, "`xx` is not a quantity"),
    (dict(record=[3]), TypeError, "record"),
    (dict(stop_when="x ~ 50"), ValueError, "`stop_when` `x ~ 50`"),
    (dict(stop_when="x > -1"), ValueError, "already holds at the start"),
    (dict(every=0), ValueError, "every"),
    (dict(from_=20.0), ValueError, "`until=10` must be finite and not before the start time 20"),
]


@pytest.mark.parametrize("overrides, exception, names", BAD_RUNS)
def test_a_bad_argument_names_itself(sled, overrides, exception, names):
    with pytest.raises(exception) as caught:
        run_sled(sled, **overrides)
    assert names in str(caught.value)
    # Python's users typed no flag: no message names one (`set=`, `stop_when=`, ...).
    for flag in ("--set", "--method", "--stop-when", "--until", "--step", "--init"):
        assert flag not in str(caught.value), str(caught.value)


def test_bad_model_arguments_name_themselves():
    with pytest.raises(TypeError, match="text must be a string"):
        varmass.Model(42)
    with pytest.raises(ValueError, match="impakt"):
        varmass.Model.from_file(MODELS / "sled.vms", with_=["impakt"])
    with pytest.raises(TypeError, match="with_ names must be strings"):
        varmass.Model.from_file(MODELS / "sled.vms", with_=[1])
    with pytest.raises(TypeError, match="path"):
        varmass.Model.from_file(3.5)
    with pytest.raises(FileNotFoundError):
        varmass.Model.from_file(MODELS / "no_such_model.vms")


def test_bad_ensemble_arguments_name_themselves(rocket):
    good = dict(
        sample={"mu": varmass.uniform(9.5, 10.5)},
        set={"u_e": 2500.0, "g": 9.81},
        init={"y": 0, "m": 1000},
        until=1e4,
        stop_when="m = 400",
        observables=["y"],
    )

    def make(**overrides):
        return rocket.ensemble(7, **{**good, **overrides})

    with pytest.raises(TypeError, match=r"sample\['mu'\]"):
        make(sample={"mu": (9.5, 10.5)})
    with pytest.raises(TypeError, match="sample must be a dict"):
        make(sample=[("mu", varmass.uniform(9.5, 10.5))])
    with pytest.raises(ValueError, match="low must be below high"):
        varmass.uniform(3, 1)
    with pytest.raises(ValueError, match="standard deviation"):
        varmass.normal(10, -1)
    with pytest.raises(ValueError, match="set and sample both give mu"):
        make(set={"mu": 10.0, "u_e": 2500.0, "g": 9.81})
    with pytest.raises(ValueError, match="`apex` is not a quantity"):
        make(observables=["apex"])
    with pytest.raises(ValueError, match="`m_dry` is not a parameter"):
        make(sample={"mu": varmass.uniform(9.5, 10.5), "m_dry": varmass.uniform(1, 2)})
    with pytest.raises(TypeError, match="seed must be an integer"):
        rocket.ensemble(1.5, **good)
    with pytest.raises(ValueError, match="observables: give 1 to 8"):
        make(observables=[])
    ensemble = make()
    with pytest.raises(ValueError, match="n must be at least 0"):
        ensemble.run(-1)
    with pytest.raises(TypeError, match="n must be an integer"):
        ensemble.run("10")
    with pytest.raises(ValueError, match="shard"):
        ensemble.run_shard(4, 4, 100)
    with pytest.raises(ValueError, match="threads must be at least 1"):
        ensemble.run(10, threads=0)


def test_a_run_after_a_remembered_one_still_checks_its_arguments(sled):
    # Model.run remembers the last run's flags by its arguments (_checks.plain_key): True
    # equals 1 but is refused, and must still be; a changed argument must change the run.
    first = run_sled(sled, init={"x": 1})
    with pytest.raises(TypeError, match=r"init\['x'\] must be a number, not bool"):
        run_sled(sled, init={"x": True})
    with pytest.raises(TypeError, match="until must be a number, not bool"):
        run_sled(sled, init={"x": 1}, until=True)
    with pytest.raises(TypeError, match=r"set\['g'\] must be a number, not bool"):
        run_sled(sled, init={"x": 1}, set={**SLED, "g": True})
    with pytest.raises(ValueError, match="`g` is given twice"):
        run_sled(sled, init={"x": 1}, set={**SLED, " g": 9.81})
    again = run_sled(sled, init={"x": 1.0})
    assert again["x"].tobytes() == first["x"].tobytes()
    assert run_sled(sled, init={"x": 1}, record=["x"]).names == ["x"]
