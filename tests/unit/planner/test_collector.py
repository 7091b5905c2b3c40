"""The cycle collector is paused while PDDL is read and grounded, and always left as it was found."""

import gc
from collections.abc import Iterator
from contextlib import contextmanager

import pytest

from semgoal_planner.blocksworld import DOMAIN_PATH, problem
from strips_planner.collector import collector_paused
from strips_planner.grounding import ground
from strips_planner.pddl import parse_domain, parse_problem


@contextmanager
def collecting_at_every_allocation() -> Iterator[list[int]]:
    """The generations collected inside the block, with the collector set to run at every allocation."""
    collected: list[int] = []

    def record(phase: str, info: dict) -> None:
        if phase == "start":
            collected.append(info["generation"])

    threshold = gc.get_threshold()
    gc.callbacks.append(record)
    gc.set_threshold(1)
    try:
        yield collected
    finally:
        gc.set_threshold(*threshold)
        gc.callbacks.remove(record)


def test_reading_and_grounding_run_no_collection() -> None:
    domain_text, problem_text = DOMAIN_PATH.read_text(), problem(8, seed=1)
    with collecting_at_every_allocation() as collections:
        domain = parse_domain(domain_text)
        grounded = ground(domain, parse_problem(problem_text, domain))
        assert collections == [] and gc.isenabled()  # 611 collections with the collector left on
        after = [[] for _ in range(3)]  # the collector runs again once they return
        assert collections
    assert len(grounded.operators) > 0 and after


def test_the_collector_is_restored_after_an_error() -> None:
    @collector_paused
    def fails() -> None:
        assert not gc.isenabled()
        raise ValueError("bad input")

    with pytest.raises(ValueError, match="bad input"):
        fails()
    assert gc.isenabled()


def test_a_collector_already_off_stays_off() -> None:
    seen = []
    paused = collector_paused(lambda: seen.append(gc.isenabled()))
    gc.disable()
    try:
        paused()
        assert not gc.isenabled()
    finally:
        gc.enable()
    paused()
    assert seen == [False, False] and gc.isenabled()
