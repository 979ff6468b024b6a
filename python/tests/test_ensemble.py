"""Ensembles from Python: 10⁴ rockets give the same bytes through `run`, four shards merged
in two orders, and `varmass.dask.run` on a two-worker LocalCluster; every member matches its
closed form; failures keep index, parameters and message."""

import math
import pickle

import numpy as np
import pytest

import varmass

MEMBERS = 10_000
M0, DRY, G = 1000.0, 400.0, 9.81


@pytest.fixture(scope="module")
def ensemble(rocket):
    """Vertical rockets burning from rest to the dry mass (stop_when m = 400)."""
    return rocket.ensemble(
        2015,
        sample={"mu": varmass.uniform(9.5, 10.5), "u_e": varmass.normal(2500, 50)},
        set={"g": G},
        init={"y": 0, "m": M0},
        until=1e4,
        stop_when=f"m = {DRY}",
        observables=["y", "y'", "t"],
    )


@pytest.fixture(scope="module")
def whole(ensemble):
    return ensemble.run(MEMBERS)


def same_bytes(a, b):
    """Bit-identical results: equal partials (values, indices, failures) and equal bytes of
    every column and statistic."""
    assert a == b
    for name in a.observables:
        assert a[name].tobytes() == b[name].tobytes()
        assert a.summary(name) == b.summary(name)
    assert a.completed.tobytes() == b.completed.tobytes()


def test_every_member_is_at_burnout_as_the_closed_form_says(whole):
    """Burning from rest, m = m0 − μ t: t_b = (m0 − m_dry)/μ, v_b = u_e ln(m0/m_dry) − g t_b,
    y_b = u_e (t_b − (m_dry/μ) ln(m0/m_dry)) − ½ g t_b². A result keeps no parameters of
    its completed members, so μ and u_e are read back from t_b and v_b, and y_b must then
    follow from them."""
    assert whole.member_count == MEMBERS and whole.failures == []
    ratio = math.log(M0 / DRY)
    t_b = whole["t"]
    mu = (M0 - DRY) / t_b
    u_e = (whole["y'"] + G * t_b) / ratio
    assert np.all((mu >= 9.5 - 1e-6) & (mu < 10.5 + 1e-6))
    exact_y = u_e * (t_b - DRY / mu * ratio) - 0.5 * G * t_b**2
    worst = np.max(np.abs(whole["y"] - exact_y) / exact_y)
    # Dormand–Prince at the default tolerance 1e-9; measured 5.6e-10.
    assert worst < 5e-9, worst
    # The normal's mean and spread come back (10⁴ draws: the mean within 4 standard errors,
    # the standard deviation within 5 %).
    assert abs(np.mean(u_e) - 2500) < 4 * 50 / math.sqrt(MEMBERS)
    assert abs(np.std(u_e) / 50 - 1) < 0.05


def test_a_member_is_the_model_run_with_its_parameters(rocket, ensemble, whole):
    """Member 4321 alone gives its sampled parameters; Model.run with them gives the same
    bits as the ensemble did: a member is exactly a run."""
    parameters, values = ensemble.member(4321)
    assert list(parameters) == ["mu", "u_e"]
    assert values == {"y": whole["y"][4321], "y'": whole["y'"][4321], "t": whole["t"][4321]}
    sol = rocket.run(set={"g": G, **parameters}, init={"y": 0, "m": M0}, until=1e4,
                     stop_when=f"m = {DRY}", record=["y", "y'"])
    assert (sol["y"][-1], sol["y'"][-1], sol.t[-1]) == (values["y"], values["y'"], values["t"])


def test_four_shards_merged_in_two_orders_are_the_whole_run(ensemble, whole):
    shards = [ensemble.run_shard(i, 4, MEMBERS) for i in range(4)]
    assert [s.covered for s in shards] == [[(0, 2500)], [(2500, 5000)], [(5000, 7500)], [(7500, 10000)]]
    forward = shards[0].merge(shards[1]).merge(shards[2]).merge(shards[3])
    backward = shards[3].merge(shards[1]).merge(shards[2].merge(shards[0]))
    same_bytes(forward, whole)
    same_bytes(backward, whole)
    with pytest.raises(ValueError, match="member 0 is in both partials"):
        shards[0].merge(forward)


def test_threads_do_not_change_a_bit(ensemble, whole):
    same_bytes(ensemble.run(MEMBERS, threads=2), whole)


def test_results_and_ensembles_pickle_exactly(ensemble, whole):
    same_bytes(pickle.loads(pickle.dumps(whole)), whole)
    again = pickle.loads(pickle.dumps(ensemble))
    same_bytes(again.run(100), ensemble.run(100))


def test_dask_on_two_worker_processes_is_bit_identical(ensemble, whole):
    distributed = pytest.importorskip("dask.distributed")
    import varmass.dask

    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        same_bytes(varmass.dask.run(client, ensemble, MEMBERS), whole)
        same_bytes(varmass.dask.run(client, ensemble, MEMBERS, shards=3), whole)


def test_failures_keep_index_parameters_and_message(rocket):
    """Rockets on full burn (μ = 10 kg/s, m0 = 1000 kg) asked to climb to 250 km. At burnout
    (m → 0 at t = 100 s) the height is y = u_e·100 − g·100²/2 (the closed form's limit, the
    log term vanishing), so those with u_e < (250 000 + 49 050)/100 = 2990.5 m/s fail with a
    mass that is no longer positive; the others stop at 250 km."""
    ensemble = rocket.ensemble(
        5,
        sample={"u_e": varmass.uniform(2000, 5000)},
        set={"g": G, "mu": 10.0},
        init={"y": 0, "m": M0},
        until=1e4,
        stop_when="y = 250000",
        observables=["t"],
    )
    result = ensemble.run(200)
    # About a third fail: (2990.5 − 2000)/3000 of 200 ≈ 66.
    assert 30 < len(result.failures) < 110, len(result.failures)
    assert len(result.failures) + len(result.completed) == 200
    assert sorted([f.index for f in result.failures] + result.completed.tolist()) == list(range(200))
    assert all(set(f.parameters) == {"u_e"} for f in result.failures)
    assert all(2000 <= f.parameters["u_e"] < 2990.5 for f in result.failures)
    failure = result.failures[0]
    assert "the mass `m` is not positive" in failure.message
    # The same member through Model.run fails with the same message.
    with pytest.raises(varmass.RunError) as caught:
        rocket.run(set={"g": G, "mu": 10.0, **failure.parameters}, init={"y": 0, "m": M0},
                   until=1e4, stop_when="y = 250000")
    assert failure.message == "the run failed: " + str(caught.value)


def test_a_named_observable_is_named_as_record_names_it(rocket):
    """`"MU=mu"` is a column named `MU`, as `--record "MU=mu"` names it (before, the
    whole text `MU=mu` was its name). Its value is the member's μ: burning from rest to
    the dry mass takes t_b = (m0 − m_dry)/μ, so MU·t_b = m0 − m_dry."""
    ensemble = rocket.ensemble(
        7,
        sample={"mu": varmass.uniform(9.5, 10.5)},
        set={"g": G, "u_e": 2500.0},
        init={"y": 0, "m": M0},
        until=1e4,
        stop_when=f"m = {DRY}",
        observables=["MU=mu", "t"],
    )
    result = ensemble.run(20)
    assert result.observables == ["MU", "t"]
    # Dormand–Prince locates the stop to ~1e-12 relative; asserted to 1e-9.
    assert np.allclose(result["MU"] * result["t"], M0 - DRY, rtol=1e-9, atol=0)
    params, values = ensemble.member(3)
    assert set(values) == {"MU", "t"} and values["MU"] == params["mu"]
