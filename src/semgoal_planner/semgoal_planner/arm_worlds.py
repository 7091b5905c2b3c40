"""The world states a planner with two arms gives steps by (where each block and hand is), kept by (episode, step).

The semantic state and the world state it was derived from come on two topics, and either may come first. A
semantic state whose world state has not come is held back until it does, so each decision is made on the
world it was derived from, whatever the order (as in the in-process episode, which the graph must reproduce step
for step). No ROS here: the planner node feeds it.
"""

from __future__ import annotations

from typing import Generic, Protocol, TypeVar

WORLDS_KEPT = 8
"""World states kept: the one each semantic state was derived from is among them (lockstep runs a step or two ahead)."""


class Stamped(Protocol):
    episode: int
    step: int


World = TypeVar("World", bound=Stamped)
State = TypeVar("State", bound=Stamped)


def stamp(message: Stamped) -> tuple[int, int]:
    return int(message.episode), int(message.step)


class ArmWorlds(Generic[World, State]):
    """World states by stamp, and at most one semantic state held back for its world."""

    def __init__(self, kept: int = WORLDS_KEPT) -> None:
        self.kept = kept
        self.worlds: dict[tuple[int, int], World] = {}
        self.held: State | None = None

    def world_of(self, state: Stamped | None) -> World | None:
        """The world state ``state`` was derived from, else the latest one (None before any came)."""
        world = self.worlds.get(stamp(state)) if state is not None else None
        return world or (self.worlds[next(reversed(self.worlds))] if self.worlds else None)

    def hold_back(self, state: State) -> bool:
        """Whether ``state`` waits for its world state; if so it is the one decided on when that comes (a newer
        state replaces it, and one decided now drops it)."""
        self.held = None if stamp(state) in self.worlds else state
        return self.held is not None

    def add(self, world: World) -> State | None:
        """Keep ``world``; return the held-back semantic state to decide on now: its world has come, or a later one
        has (its own will not, and a decision on the latest is better than none)."""
        self.worlds[stamp(world)] = world
        if len(self.worlds) > self.kept:
            del self.worlds[next(iter(self.worlds))]
        held = self.held
        if held is None or stamp(held) > stamp(world):
            return None
        self.held = None
        return held
