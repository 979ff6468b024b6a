"""Tables and inputs given data from Python (``tables=``, ``inputs=``): the tool's ``--table``
and ``--input u=FILE`` (docs/tables.md#runtime-tables), a path as the tool takes it or
arrays written to a file the tool reads; against the model with the same data in its own
statement (which the tool's tests hold equal to ``--table``, cli/tests/runtime_tables.rs)
and a closed form."""

import math
import pathlib
import pickle

import numpy as np
import pytest

import varmass
from conftest import MODELS

DATA = pathlib.Path(__file__).resolve().parents[2] / "cli" / "tests" / "data"
M1670 = MODELS / "motors" / "Cesaroni_M1670.eng"
K828 = MODELS / "motors" / "AeroTech_K828FJ.eng"


def eng_points(path):
    """A RASP file's thrust curve as the tool's reader gives it (docs/tables.md): the
    header line skipped, (0 s, 0 N) put first when the file does not list t = 0."""
    rows = [line.split() for line in pathlib.Path(path).read_text().splitlines()]
    points = [(float(t), float(f)) for t, f in (r for r in rows[1:] if len(r) == 2)]
    if points[0][0] != 0.0:
        points.insert(0, (0.0, 0.0))
    t, f = zip(*points)
    return np.array(t), np.array(f)


#: The M1670's flight of cli/tests/runtime_tables.rs, to 6 s at tolerance 1e-10.
FLIGHT = dict(
    set={"u_e": 2000.0, "g": 9.80665},
    init={"y": 0, "m": 20},
    until=6,
    tol=1e-10,
    record=["y", "y'", "m"],
)


def flight(path, **extra):
    return varmass.Model.from_file(path).run(**FLIGHT, **extra)


def assert_same_bits(a, b):
    assert len(a) > 20, len(a)  # the curve's knots are stop times: many rows
    assert a.names == b.names
    for name in a.keys():
        assert np.array_equal(a[name], b[name]), name
    assert a.statistics == b.statistics


@pytest.fixture(scope="module")
def file_table():
    return flight(MODELS / "motor_rocket.vms")


def test_a_runtime_table_given_a_path_flies_as_the_file_table_to_the_bit(file_table, monkeypatch):
    given = flight(MODELS / "motor_rocket_runtime.vms", tables={"F": M1670})
    assert_same_bits(given, file_table)
    # A relative path is the tool's: relative to the current directory.
    monkeypatch.chdir(MODELS)
    relative = flight(MODELS / "motor_rocket_runtime.vms", tables={"F": "motors/Cesaroni_M1670.eng"})
    assert_same_bits(relative, file_table)


def test_a_table_given_by_arrays_flies_as_the_file_to_the_bit(file_table):
    t, f = eng_points(M1670)
    given = flight(MODELS / "motor_rocket_runtime.vms", tables={"F": (t, f)})
    assert_same_bits(given, file_table)
    # Lists do as well as arrays.
    listed = flight(MODELS / "motor_rocket_runtime.vms", tables={"F": [list(t), list(f)]})
    assert_same_bits(listed, file_table)


def test_tables_replace_a_file_tables_data_and_change_between_runs():
    """``tables`` for a file table replaces its file (as ``--table`` does); a model run with
    one motor, then another, then the first again flies each as its own file."""
    model = varmass.Model.from_file(MODELS / "motor_rocket.vms")
    m1670 = model.run(**FLIGHT)
    k828 = model.run(**FLIGHT, tables={"F": K828})
    again = model.run(**FLIGHT)
    arrays = model.run(**FLIGHT, tables={"F": eng_points(K828)})
    assert not np.array_equal(m1670["y"][-1:], k828["y"][-1:])
    assert_same_bits(again, m1670)
    assert_same_bits(arrays, k828)
    runtime_k828 = flight(MODELS / "motor_rocket_runtime.vms", tables={"F": str(K828)})
    assert_same_bits(runtime_k828, k828)


def test_a_table_file_rewritten_between_runs_is_read_again(tmp_path, file_table):
    """A model keeps what it derived for a run's data, but a file written again between two
    runs (a notebook saving another curve to the same path) is read again, as the tool,
    which reads it at each run, would."""
    path = tmp_path / "motor.eng"
    model = varmass.Model.from_file(MODELS / "motor_rocket_runtime.vms")
    path.write_text(K828.read_text())
    k828 = model.run(**FLIGHT, tables={"F": path})
    # A comment makes another length, whatever the grain of the file system's clock.
    path.write_text(M1670.read_text() + "; the M1670 again\n")
    assert_same_bits(model.run(**FLIGHT, tables={"F": path}), file_table)
    assert not np.array_equal(k828["y"][-1:], file_table["y"][-1:])


def test_a_linear_thrust_meets_the_closed_form():
    """F(t) = a + b t on [0, T] given as four knots (linear interpolation reproduces a line):
    with g = 0, ṁ = −F/u_e gives m(T) = m0 − I(T)/u_e with I(T) = a T + b T²/2, and
    Meshchersky's ẏ' = F/m = −u_e ṁ/m gives ẏ(T) = u_e ln(m0/m(T)). m0 = 20 kg,
    u_e = 2000 m/s, a = 1000 N, b = −200 N/s, T = 3 s: I = 2100 N s, m(T) = 18.95 kg,
    ẏ(T) = 2000 ln(20/18.95) = 107.86… m/s."""
    t = np.array([0.0, 1.0, 2.0, 3.0])
    model = varmass.Model.from_file(MODELS / "motor_rocket_runtime.vms")
    sol = model.run(
        set={"u_e": 2000.0, "g": 0.0},
        init={"y": 0, "m": 20},
        until=3,
        method="dop853",
        tol=1e-12,
        record=["y'", "m"],
        tables={"F": (t, 1000.0 - 200.0 * t)},
    )
    m_end = 20.0 - (1000.0 * 3 - 200.0 * 9 / 2) / 2000.0
    v_end = 2000.0 * math.log(20.0 / m_end)
    assert sol.t[-1] == 3.0
    # Measured 1.9e-16 (m) and 1.7e-15 (ẏ) relative (DOP853 at 1e-12, 10 steps); bound 1e-13.
    assert abs(sol["m"][-1] - m_end) <= 1e-13 * m_end, sol["m"][-1]
    assert abs(sol["y'"][-1] - v_end) <= 1e-13 * v_end, (sol["y'"][-1], v_end)


def test_an_input_given_a_file_or_arrays_runs_as_the_dsl_table():
    """``inputs={"u": FILE}`` is ``--input u=FILE``: the input becomes a linear table of its
    first argument, as cli/tests/data/hover_table.vms writes the same data in the model."""
    hover = dict(
        set={"u_e": 2000.0, "g": 9.80665}, init={"y": 0, "m": 50}, until=15, tol=1e-10
    )
    written = varmass.Model.from_file(DATA / "hover_table.vms").run(**hover)
    model = varmass.Model.from_file(DATA / "hover_input.vms")
    path = DATA / "tables" / "hover_u.csv"
    assert_same_bits(model.run(inputs={"u": path}, **hover), written)
    data = np.loadtxt(path, delimiter=",", comments="#", skiprows=1)
    assert_same_bits(model.run(inputs={"u": (data[:, 0], data[:, 1])}, **hover), written)


def rocket_ensemble(path, **data):
    model = varmass.Model.from_file(path)
    return model.ensemble(
        7,
        sample={"u_e": varmass.uniform(1900, 2100)},
        set={"g": 9.80665},
        init={"y": 0, "m": 20},
        until=6,
        tol=1e-10,
        observables=["y", "m"],
        **data,
    )


def test_an_ensemble_takes_tables_and_pickles_with_them(tmp_path, monkeypatch):
    """An ensemble's members fly the given data as the file table; a pickled ensemble
    (what Dask sends to a worker) carries arrays and absolute paths, so it runs the same
    from another directory."""
    reference = rocket_ensemble(MODELS / "motor_rocket.vms").run(24, threads=2)
    runtime = MODELS / "motor_rocket_runtime.vms"
    monkeypatch.chdir(MODELS)
    by_path = rocket_ensemble(runtime, tables={"F": "motors/Cesaroni_M1670.eng"})
    by_arrays = rocket_ensemble(runtime, tables={"F": eng_points(M1670)})
    assert not reference.failures and reference.member_count == 24
    assert by_path.run(24, threads=2) == reference
    assert by_arrays.run(24) == reference
    monkeypatch.chdir(tmp_path)
    for ensemble in (by_path, by_arrays):
        assert pickle.loads(pickle.dumps(ensemble)).run(24) == reference


BASE = dict(set={"u_e": 1000.0, "g": 9.8}, init={"y": 0, "m": 20}, until=1)


@pytest.mark.parametrize(
    "tables, error, match",
    [
        ({"F": "missing.eng"}, ValueError, "--table F: cannot read the table file `missing.eng`"),
        ({"F": str(MODELS / "motor_rocket.vms")}, ValueError, r"a RASP motor \(`.eng`\) or a CSV table"),
        ({"G": M1670}, ValueError, "`G` is not a table of the model"),
        ({"F": M1670, " F": K828}, ValueError, "--table F is given twice"),
        ({"F": ([0.0, 1.0], [1.0])}, ValueError, r"tables\['F'\]: 2 arguments but 1 values"),
        ({"F": ([0.0, 2.0, 1.0], [1.0, 2.0, 3.0])}, ValueError, "must increase, but 1.0 follows 2.0"),
        ({"F": ([0.0, 1.0], [1.0, math.nan])}, ValueError, "must be finite"),
        ({"F": ([0.0], [1.0])}, ValueError, "at least two points, not 1"),
        ({"F": (np.zeros((2, 2)), np.zeros((2, 2)))}, ValueError, "must be 1-D"),
        ({"F": ([0.0, 1.0], [1.0, 2.0], [3.0, 4.0])}, ValueError, "a pair"),
        ({"F": (["a", "b"], [1.0, 2.0])}, TypeError, "must be numbers"),
        ({"F": 3.0}, TypeError, r"tables\['F'\] must be a path"),
        ({1: M1670}, TypeError, "tables names must be strings"),
        ({"F=x": M1670}, ValueError, r"tables: 'F=x' is not a table name"),
        ([("F", M1670)], TypeError, "tables must be a mapping"),
    ],
)
def test_table_mistakes_are_the_tools_errors(tables, error, match):
    model = varmass.Model.from_file(MODELS / "motor_rocket_runtime.vms")
    with pytest.raises(error, match=match):
        model.run(**BASE, tables=tables)


def test_a_runtime_table_without_data_and_a_model_without_tables_are_refused(sled):
    model = varmass.Model.from_file(MODELS / "motor_rocket_runtime.vms")
    with pytest.raises(ValueError, match=r"table `F` is `= runtime`.*--table F="):
        model.run(**BASE)
    with pytest.raises(ValueError, match="--table F: the model declares no table"):
        sled.run(set={"m0": 10.0}, init={"x": 0}, until=1, tables={"F": M1670})


def test_a_bad_table_file_is_refused_with_its_line(tmp_path):
    bad = tmp_path / "bad_motor.eng"
    bad.write_text("M1 75 757 0 3.0 5.0 X\n0.5 100\n1.O 50\n")
    model = varmass.Model.from_file(MODELS / "motor_rocket_runtime.vms")
    with pytest.raises(ValueError, match="bad_motor.eng:3:1: `1.O` is not a number"):
        model.run(**BASE, tables={"F": bad})
    with pytest.raises(TypeError, match=r"inputs\['u'\] must be a law"):
        varmass.Model.from_file(DATA / "hover_input.vms").run(**BASE, inputs={"u": 1.0})


def test_arrays_for_a_table_declared_from_an_eng_file_start_from_zero_thrust(file_table):
    """``tables={"F": (t, F)}`` for a table whose statement names a RASP ``.eng`` file is
    read as such a file: from (0 s, 0 N) when the points do not list t = 0, as the
    declared file's curve (before, the arrays became a CSV table that began at the first
    point, so the 0.055 s ramp from zero thrust was lost, silently).

    By hand: ṁ = −F/u_e, so after burnout m = m₀ − I/u_e with I the exact trapezoid
    integral of the curve from (0, 0); bound 1e-11 relative to m (measured near 1e-15:
    the knots are stop times, the burn linear between them)."""
    rows = [line.split() for line in M1670.read_text().splitlines()]
    t, f = (np.array(c) for c in zip(*[(float(a), float(b)) for a, b in (r for r in rows[1:] if len(r) == 2)]))
    assert t[0] > 0.0  # the file does not list t = 0: the reader adds (0, 0)
    given = flight(MODELS / "motor_rocket.vms", tables={"F": (t, f)})
    assert_same_bits(given, file_table)
    t0, f0 = np.concatenate(([0.0], t)), np.concatenate(([0.0], f))
    impulse = float(np.sum(0.5 * (f0[1:] + f0[:-1]) * np.diff(t0)))
    assert t[-1] < FLIGHT["until"]  # burnt out before the end
    m_end = 20.0 - impulse / FLIGHT["set"]["u_e"]
    assert abs(given["m"][-1] - m_end) <= 1e-11 * m_end, (given["m"][-1], m_end)
    # The ramp from zero is what the CSV table lost: ½·0.055 s·100 N of impulse.
    lost = 0.5 * t[0] * f[0]
    assert lost > 1.0 and abs(given["m"][-1] - (m_end + lost / FLIGHT["set"]["u_e"])) > 1e-4


def test_a_table_and_a_sqrt_are_recorded():
    """``record=["F", "S=sqrt(F)"]``: the model's table at the argument it calls it with
    (``F(t)``) and an expression calling ``sqrt`` (both refused before). F is the RASP
    curve, linear between its points (``eng_points``), 0 outside."""
    model = varmass.Model.from_file(MODELS / "motor_rocket.vms")
    solution = model.run(**{**FLIGHT, "record": ["F", "S=sqrt(F)"]})
    t, f = eng_points(M1670)
    exact = np.interp(solution["t"], t, f, right=0.0)
    # Linear interpolation of the same points: to rounding (bound 1e-12 of the peak).
    assert np.max(np.abs(solution["F"] - exact)) <= 1e-12 * f.max()
    assert np.array_equal(solution["S"], np.sqrt(solution["F"]))
