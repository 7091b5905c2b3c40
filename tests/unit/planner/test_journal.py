"""The planner's journal: the executive's state survives a restart on the same world, and only there."""

import sqlite3

import pytest
from test_executive import executive, observe

from semgoal_planner.journal import JOURNAL_FILE, PlanJournal, Record, Verdict, World, resume

WORLD = World("desk_cleanup", ("red", "green", "blue"), episode=3, sim_time=12.5)


def edited_plan():
    """A plan under way with an operator's edit (the last put is a person's) and its first step done."""
    ex = executive()
    assert ex.set_goal("in_bin(red) & in_bin(green)")[0]
    ex.observe(observe(["holding(green)"], 20))
    assert ex.edit("assign", 3, action="human")[0], ex.message
    return ex


def test_a_plan_with_edits_comes_back_equal(tmp_path) -> None:
    ex = edited_plan()
    journal = PlanJournal(tmp_path)
    journal.save(Record(ex.snapshot(), WORLD, action_goal="ab" * 16))
    journal.close()

    record = PlanJournal(tmp_path).load()
    assert record.world == WORLD and record.action_goal == "ab" * 16
    restored = executive()
    restored.restore(record.executive, "restored")
    assert restored.snapshot() | {"message": ex.message} == ex.snapshot()  # the active step stays active
    assert [(str(a.subgoal), a.assignee) for a in restored.steps] == [(str(b.subgoal), b.assignee) for b in ex.steps]
    assert (restored.revision, restored.current, restored.status) == (ex.revision, ex.current, ex.status)


def test_the_restored_active_step_is_checked_against_the_world_before_it_runs_again() -> None:
    ex = edited_plan()
    restored = executive()
    restored.restore(ex.snapshot(), "restored")
    restored.observe(observe(["in_bin(green)"], 60))  # the put finished while the planner was away
    assert restored.steps[1].status == "done" and restored.current >= 2
    assert restored.revision > ex.revision


def test_the_journal_is_in_wal_mode_and_one_row(tmp_path) -> None:
    journal = PlanJournal(tmp_path)
    for revision in range(5):
        journal.save(Record({"revision": revision}, WORLD))
    with sqlite3.connect(tmp_path / JOURNAL_FILE) as db:
        assert db.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
        assert db.execute("SELECT COUNT(*) FROM journal").fetchone()[0] == 1
    assert journal.load().executive == {"revision": 4}
    journal.clear()
    assert journal.load() is None


@pytest.mark.parametrize("now, reason", [
    (World("desk_cleanup", ("red", "green"), 3, 13.0), "had red, green, blue; this one has red, green"),
    (World("desk_cleanup", ("red", "green", "blue"), 4, 13.0), "episode 3; the world is at episode 4"),
    (World("desk_cleanup", ("red", "green", "blue"), 3, 1.0), "the sim started again"),
    (World("two_blocks", ("red", "green", "blue"), 3, 13.0), "scene desk_cleanup"),
])
def test_another_world_is_refused_with_the_reason(now: World, reason: str) -> None:
    verdict, message = resume(Record({}, WORLD), now)
    assert verdict == Verdict.DISCARD and reason in message


def test_the_same_world_is_taken_up_once_a_state_as_new_as_the_journal_comes() -> None:
    """A restarted planner first hears the latched states of the steps before its journal was saved."""
    later = World("desk_cleanup", ("red", "green", "blue"), 3, 12.6)
    latched = World("desk_cleanup", ("red", "green", "blue"), 3, 12.2)
    assert resume(Record({}, WORLD), later)[0] == Verdict.RESUME
    assert resume(Record({}, WORLD), latched)[0] == Verdict.WAIT


def test_an_unreadable_record_is_none_and_a_misfit_plan_is_refused(tmp_path) -> None:
    journal = PlanJournal(tmp_path)
    journal._db.execute("INSERT OR REPLACE INTO journal (id, record) VALUES (1, 'not json')")
    assert journal.load() is None
    with pytest.raises(ValueError, match="does not fit scene desk_cleanup"):
        executive().restore({"steps": [{"subgoal": "put_on(red,green)", "status": "pending", "assignee": "robot"}],
                             "goal": [], "status": "executing"}, "restored")
