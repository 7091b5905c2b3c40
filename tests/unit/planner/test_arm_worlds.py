"""Two arms: a semantic state is decided on the world state it was derived from, whichever of the two came first."""

from types import SimpleNamespace

from semgoal_planner.arm_worlds import ArmWorlds


def message(episode: int, step: int, name: str = "") -> SimpleNamespace:
    return SimpleNamespace(episode=episode, step=step, name=name)


def test_a_state_whose_world_came_first_is_decided_at_once() -> None:
    worlds = ArmWorlds()
    world = message(1, 0, "world")
    assert worlds.add(world) is None
    state = message(1, 0)
    assert not worlds.hold_back(state)
    assert worlds.world_of(state) is world


def test_a_state_before_its_world_waits_for_it() -> None:
    worlds = ArmWorlds()
    worlds.add(message(0, 7, "the world before the reset"))
    state = message(1, 0)
    assert worlds.hold_back(state)
    assert worlds.add(message(0, 8)) is None  # an older world does not release it
    assert worlds.add(message(1, 0, "its world")) is state
    assert worlds.world_of(state).name == "its world"
    assert worlds.add(message(1, 1)) is None  # decided once


def test_a_newer_state_replaces_the_one_held_and_one_decided_drops_it() -> None:
    worlds = ArmWorlds()
    assert worlds.hold_back(message(1, 3))
    newer = message(1, 4)
    assert worlds.hold_back(newer)
    assert worlds.add(message(1, 3)) is None
    assert worlds.add(message(1, 4)) is newer
    assert worlds.hold_back(message(1, 5))
    worlds.add(message(1, 6))
    assert not worlds.hold_back(message(1, 6))
    assert worlds.held is None


def test_a_lost_world_releases_its_state_on_the_next() -> None:
    worlds = ArmWorlds()
    state = message(2, 10)
    assert worlds.hold_back(state)
    assert worlds.add(message(2, 11, "latest")) is state
    assert worlds.world_of(state).name == "latest"


def test_only_the_latest_worlds_are_kept() -> None:
    worlds = ArmWorlds(kept=3)
    for step in range(5):
        worlds.add(message(1, step, str(step)))
    assert list(worlds.worlds) == [(1, 2), (1, 3), (1, 4)]
    assert worlds.world_of(None).name == "4"
    assert ArmWorlds().world_of(message(1, 0)) is None
