"""The planner's journal: what it was doing, kept on disk so that a planner started again carries on. No ROS.

One SQLite database in WAL mode (a write is one small transaction that a kill cannot leave half done) holds
one record, rewritten on every change of the plan: the executive's goal, steps with their edits and
assignments, revision and active step (:meth:`Executive.snapshot`), the world it was for (scene, blocks,
episode, sim time) and the action goal then in flight. :meth:`PlanJournal.resume` decides whether a
restarted planner may take the record up: only on the same world, never on one reset or started again.
"""

from __future__ import annotations

import json
import sqlite3
import time
from dataclasses import asdict, dataclass, field
from enum import StrEnum
from pathlib import Path

JOURNAL_FILE = "planner-journal.sqlite"


@dataclass(frozen=True)
class World:
    """The world a plan was made for, as the semantic states name it."""

    scene: str
    objects: tuple[str, ...]
    episode: int
    sim_time: float


@dataclass
class Record:
    """One journal entry: the executive's state, its world and the action goal in flight (uuid hex, '' if none)."""

    executive: dict
    world: World
    action_goal: str = ""
    saved_at: float = field(default_factory=time.time)


class PlanJournal:
    """The journal in ``directory`` (created if missing)."""

    def __init__(self, directory: Path | str) -> None:
        self.path = Path(directory) / JOURNAL_FILE
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._db = sqlite3.connect(self.path, isolation_level=None, check_same_thread=False)
        self._db.execute("PRAGMA journal_mode=WAL")
        self._db.execute("PRAGMA synchronous=NORMAL")  # WAL + NORMAL: a killed process loses nothing committed
        self._db.execute("CREATE TABLE IF NOT EXISTS journal (id INTEGER PRIMARY KEY CHECK (id = 1), record TEXT)")

    def save(self, record: Record) -> None:
        text = json.dumps({**asdict(record), "world": asdict(record.world)})
        self._db.execute("INSERT OR REPLACE INTO journal (id, record) VALUES (1, ?)", (text,))

    def load(self) -> Record | None:
        """The last record saved, or None (no journal yet, or one this version cannot read)."""
        row = self._db.execute("SELECT record FROM journal WHERE id = 1").fetchone()
        if row is None:
            return None
        try:
            data = json.loads(row[0])
            world = World(data["world"]["scene"], tuple(data["world"]["objects"]), int(data["world"]["episode"]),
                          float(data["world"]["sim_time"]))
            return Record(data["executive"], world, data.get("action_goal", ""), float(data["saved_at"]))
        except (ValueError, KeyError, TypeError):
            return None

    def clear(self) -> None:
        self._db.execute("DELETE FROM journal")

    def close(self) -> None:
        self._db.close()


REWIND_S = 1.0
"""How far (s of sim time) a state may lag the journal's and still be of the same world: a planner started again
first hears the latched states of the last few control steps, older than the one its journal was saved on."""


class Verdict(StrEnum):
    RESUME = "resume"
    WAIT = "wait"
    DISCARD = "discard"


def resume(record: Record, now: World) -> tuple[Verdict, str]:
    """Whether a planner that hears a state of world ``now`` may take ``record`` up, must wait for a later state
    (one of the latched states from before its journal), or must discard it; and why."""
    was = record.world
    if now.scene != was.scene:
        return Verdict.DISCARD, f"the journal is of scene {was.scene}, the world is {now.scene}"
    if now.objects != was.objects:
        return Verdict.DISCARD, f"the journal's world had {', '.join(was.objects)}; this one has {', '.join(now.objects)}"
    if now.episode != was.episode:
        return Verdict.DISCARD, f"the journal is of world episode {was.episode}; the world is at episode {now.episode}"
    if now.sim_time < was.sim_time - REWIND_S:
        return Verdict.DISCARD, (f"the world's clock ({now.sim_time:.2f} s) is behind the journal's "
                                 f"({was.sim_time:.2f} s): the sim started again")
    if now.sim_time < was.sim_time:
        return Verdict.WAIT, "a state from before the journal"
    return Verdict.RESUME, f"same world (episode {now.episode}, {', '.join(now.objects)})"
