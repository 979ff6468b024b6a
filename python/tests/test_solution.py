"""A run's `Solution` as the fast path makes it: `set` as a plain dict (checked by the
extension) gives the bits of the same values checked in Python; the end state, statistics
and summary, made when first read, are the run's; a solution pickles whole."""

import math
import pickle
import types

import numpy as np
import pytest

from conftest import SLED


def sled_to_50(sled, parameters):
    return sled.run(set=parameters, init={"x": 0}, until=100, stop_when="x = 50",
                    method="dop853", tol=1e-12, record=["x", "x'"])


def same_bits(a, b):
    assert a.names == b.names
    assert a.t.tobytes() == b.t.tobytes()
    for name in a.names:
        assert a[name].tobytes() == b[name].tobytes(), name
    assert a.end_state == b.end_state and a.end_time == b.end_time
    assert a.statistics == b.statistics and a.summary == b.summary


def test_a_plain_dict_runs_as_the_values_checked_in_python(sled):
    plain = sled_to_50(sled, SLED)
    # Each of these takes the checked path in Python: a mapping that is not a dict, an int
    # value, a key with spaces around it (stripped), a key with a non-ASCII end.
    proxy = sled_to_50(sled, types.MappingProxyType(SLED))
    ints = sled_to_50(sled, {**SLED, "m0": 10})
    spaced = sled_to_50(sled, {(" g " if k == "g" else k): v for k, v in SLED.items()})
    for other in (proxy, ints, spaced):
        same_bits(plain, other)
    # A non-finite value in a plain-looking dict is refused with the Python message.
    with pytest.raises(ValueError, match=r"set\['g'\] must be finite, not nan"):
        sled_to_50(sled, {**SLED, "g": math.nan})
    with pytest.raises(ValueError, match="`é` is not a parameter"):
        sled_to_50(sled, {**SLED, "é": 1.0})


def test_the_details_read_later_are_the_runs(sled):
    sol = sled_to_50(sled, SLED)
    # The end state [x, p] is the last recorded point: x, and p = m x' with m = m0 + c x.
    x, v = sol["x"][-1], sol["x'"][-1]
    assert sol.end_state[0] == x and sol.end_time == sol.t[-1]
    m = SLED["m0"] + SLED["c"] * x
    assert abs(sol.end_state[1] - m * v) <= 1e-12 * m * v, (sol.end_state, m * v)
    assert sol.end == {"x": x, "x'": v}
    statistics = sol.statistics
    assert statistics["accepted_steps"] == len(sol) - 1
    assert sol.summary.startswith(f"stopped at t = {sol.end_time!r} (--stop-when 'x = 50')")
    assert f"\n  x' = {float(v)!r}\n" in sol.summary
    # Read again: the same objects, made once.
    assert sol.statistics is statistics and sol.summary is sol.summary


def test_a_solution_pickles_whole(sled):
    sol = sled_to_50(sled, SLED)
    again = pickle.loads(pickle.dumps(sol))
    same_bits(sol, again)
    assert again.stopped_by == "x = 50" and again.changes == []
    np.testing.assert_array_equal(again["x"], sol["x"])
