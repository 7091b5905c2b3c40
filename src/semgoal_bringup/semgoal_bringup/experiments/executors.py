"""Where an experiment's independent jobs run: ``local`` (a pool of spawned processes on this machine) or
``dask`` (a Dask distributed ``LocalCluster`` on 127.0.0.1, one single-threaded worker process per job slot) or
``dask:ADDRESS`` (a running Dask scheduler, e.g. ``dask:tcp://10.0.0.5:8786``: the same jobs on a cluster).

Every job is seeded by its arguments, so results do not depend on the executor or the number of workers."""

from __future__ import annotations

import multiprocessing
import sys
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor

from tqdm import tqdm

EXECUTORS = ("local", "dask", "dask:ADDRESS")


def check_executor(spec: str) -> str:
    """``spec`` if it names an executor, else ValueError with the choices."""
    if spec in ("local", "dask") or (spec.startswith("dask:") and len(spec) > len("dask:")):
        return spec
    raise ValueError(f"unknown executor {spec!r}: {', '.join(EXECUTORS)}")


def run_jobs(function: Callable, jobs: Sequence[tuple], executor: str = "local", workers: int = 1,
             what: str = "job") -> list:
    """``function(*args)`` for every ``args`` of ``jobs`` on ``executor``; the results in the order of ``jobs``
    (a progress bar counts them as they finish)."""
    check_executor(executor)
    with tqdm(total=len(jobs), unit=what, desc=what, file=sys.stderr) as progress:
        if executor == "local":
            # spawned, not forked: a forked copy of a process that runs DDS threads can die at start
            with ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("spawn")) as pool:
                futures = [pool.submit(function, *args) for args in jobs]
                for future in futures:
                    future.result()
                    progress.update(1)
                return [future.result() for future in futures]
        return _run_on_dask(function, jobs, executor, workers, progress)


def _run_on_dask(function: Callable, jobs: Sequence[tuple], executor: str, workers: int, progress: tqdm) -> list:
    from distributed import Client, LocalCluster, as_completed

    address = executor.removeprefix("dask").removeprefix(":")
    cluster = None if address else LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                                host="127.0.0.1", dashboard_address=None)
    try:
        with Client(address or cluster) as client:
            futures = [client.submit(function, *args, pure=False) for args in jobs]
            for _ in as_completed(futures):
                progress.update(1)
            return client.gather(futures)
    finally:
        if cluster is not None:
            cluster.close()
