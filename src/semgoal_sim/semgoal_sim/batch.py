"""Many worlds stepped at once on threads: MuJoCo's ``mj_step`` lets go of the GIL, so each thread's share of the
worlds runs its physics on a core of its own, and throughput grows with the cores (``./semgoal bench sim`` measures
it). What a step does in Python (the mocap target, the finger targets) still takes the GIL."""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from semgoal_sim.world import FetchWorld


class WorldBatch:
    """``worlds`` stepped together, ``threads`` at a time (default: the machine's cores)."""

    def __init__(self, worlds: list[FetchWorld], threads: int | None = None) -> None:
        self.worlds = worlds
        self.threads = max(1, min(threads or os.cpu_count() or 1, len(worlds)))
        self.shares = [list(range(i, len(worlds), self.threads)) for i in range(self.threads)]
        self.pool = ThreadPoolExecutor(self.threads, thread_name_prefix="worlds") if self.threads > 1 else None

    def step(self, actions: np.ndarray) -> None:
        """One control step of every world, ``actions[i]`` for world i."""
        if self.pool is None:
            self._step_share(self.shares[0], actions)
            return
        for future in [self.pool.submit(self._step_share, share, actions) for share in self.shares]:
            future.result()

    def _step_share(self, share: list[int], actions: np.ndarray) -> None:
        for i in share:
            self.worlds[i].step(actions[i])

    def close(self) -> None:
        if self.pool is not None:
            self.pool.shutdown()

    def __enter__(self) -> WorldBatch:
        return self

    def __exit__(self, *_) -> None:
        self.close()
