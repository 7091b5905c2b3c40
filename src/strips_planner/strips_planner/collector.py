"""Reading and grounding with Python's cycle collector paused.

What the reader and the grounder build holds no reference cycles, so a collection started inside them finds
nothing to free; it still walks every young object, and right after a search has flushed the caches that walk
missed in memory for about 1 ms, as long as a whole grounding of blocksworld 12 (one run in three of
``semgoal bench planner``). Paused, the collector runs at its next trigger after the call, on warm objects.
"""

from __future__ import annotations

import functools
import gc
from collections.abc import Callable
from typing import ParamSpec, TypeVar

_P = ParamSpec("_P")
_R = TypeVar("_R")


def collector_paused(function: Callable[_P, _R]) -> Callable[_P, _R]:
    """``function`` with the cycle collector paused while it runs, and restored after (nested calls and a
    collector already off are left alone; another thread's call never leaves it off)."""

    @functools.wraps(function)
    def paused(*args: _P.args, **kwargs: _P.kwargs) -> _R:
        if not gc.isenabled():
            return function(*args, **kwargs)
        gc.disable()
        try:
            return function(*args, **kwargs)
        finally:
            gc.enable()

    return paused
