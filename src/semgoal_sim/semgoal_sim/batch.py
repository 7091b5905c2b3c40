"""Many worlds stepped at once on threads: MuJoCo's ``mj_step`` lets go of the GIL, so each thread's worlds run their
physics on a core of its own, and throughput grows with the cores (``./semgoal bench sim`` measures it). What a step
does in Python (the mocap target, the finger targets) still takes the GIL, about 3 % of a desk world's step.

Each thread, the caller's among them, takes the next world not yet stepped: worlds with more contacts take longer to
step, and a fixed share per thread left one thread idle while the other finished its slower worlds (8 desk worlds on 2
cores: 1.43x one core with a share per pool thread, 1.72x taking turns, measured in turns in one process)."""

from __future__ import annotations

import itertools
import os
import threading

import numpy as np

from semgoal_sim.world import FetchWorld


class WorldBatch:
    """``worlds`` stepped together on ``threads`` threads, the caller's included (default: the machine's cores)."""

    def __init__(self, worlds: list[FetchWorld], threads: int | None = None) -> None:
        self.worlds = worlds
        self.threads = max(1, min(threads or os.cpu_count() or 1, len(worlds)))
        self._actions: np.ndarray | None = None
        self._next = itertools.count()
        self._failure: BaseException | None = None
        self._closed = False
        self._go = [threading.Semaphore(0) for _ in range(self.threads - 1)]
        self._done = threading.Semaphore(0)
        self._helpers = [threading.Thread(target=self._help, args=(go,), name=f"worlds-{i}", daemon=True)
                         for i, go in enumerate(self._go, start=1)]
        for helper in self._helpers:
            helper.start()

    def step(self, actions: np.ndarray) -> None:
        """One control step of every world, ``actions[i]`` for world i. A world's step that raises is raised here, once
        every thread has stopped; which of the other worlds stepped is then not said."""
        if self._closed:
            raise RuntimeError("the batch is closed")
        self._actions, self._next, self._failure = actions, itertools.count(), None
        for go in self._go:
            go.release()
        try:
            self._step_some()
        finally:
            for _ in self._go:
                self._done.acquire()
        if self._failure is not None:
            raise self._failure

    def _step_some(self) -> None:
        """Step the worlds no thread has taken yet (``next`` on a count is atomic under the GIL)."""
        while (i := next(self._next)) < len(self.worlds):
            self.worlds[i].step(self._actions[i])

    def _help(self, go: threading.Semaphore) -> None:
        while True:
            go.acquire()
            if self._closed:
                return
            try:
                self._step_some()
            except BaseException as failure:  # raised again in the caller's thread
                self._failure = failure
            finally:
                self._done.release()

    def close(self) -> None:
        if self._closed:
            return
        self._closed = True
        for go in self._go:
            go.release()
        for helper in self._helpers:
            helper.join()

    def __enter__(self) -> WorldBatch:
        return self

    def __exit__(self, *_) -> None:
        self.close()
