"""Ensembles on a ``dask.distributed`` cluster: shards run on the workers and merge exactly.

>>> from dask.distributed import Client, LocalCluster          # doctest: +SKIP
>>> with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
...     result = varmass.dask.run(client, ensemble, 100_000)   # doctest: +SKIP

The result is bit-identical to ``ensemble.run(total)`` on one machine, whatever the number
of workers or shards: a member depends only on (seed, index), and the merge keeps member
order. Only the cluster object changes for Slurm, PBS (dask-jobqueue) or Kubernetes.
Needs ``pip install ./python[dask]``.
"""

from __future__ import annotations

import functools

from ._ensemble import Ensemble, EnsembleResult, _count

__all__ = ["run"]


def _shard(ensemble: Ensemble, index: int, count: int, total: int, threads: int):
    return ensemble.run_shard(index, count, total, threads=threads)


def run(client, ensemble: Ensemble, total, shards=None, threads: int = 1) -> EnsembleResult:
    """Runs ``total`` members of ``ensemble`` as ``shards`` tasks on ``client``'s workers
    (default: four per worker thread, so a slow shard does not hold up the end) and
    merges their results. Each task runs its shard on ``threads`` threads (1: Dask's
    worker threads are the parallelism)."""
    if not isinstance(ensemble, Ensemble):
        raise TypeError(f"ensemble must be a varmass.Ensemble, not {type(ensemble).__name__}")
    total = _count("total", total)
    threads = _count("threads", threads, minimum=1)
    if shards is None:
        workers = client.scheduler_info().get("workers", {})
        slots = sum(w.get("nthreads", 1) for w in workers.values()) or 1
        shards = 4 * slots
    shards = _count("shards", shards, minimum=1)
    # A fresh key each call (hash=False): a content-hashed key reused by the next call can
    # be released on the workers while that call still needs it.
    [remote] = client.scatter([ensemble], broadcast=True, hash=False)
    futures = [
        client.submit(_shard, remote, i, shards, total, threads, pure=False)
        for i in range(shards)
    ]
    results = client.gather(futures)
    return functools.reduce(EnsembleResult.merge, results)
