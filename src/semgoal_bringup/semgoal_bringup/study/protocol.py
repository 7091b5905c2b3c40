"""A study's protocol, read from YAML, and the order of its conditions for a participant.

```yaml
name: desk, together or in turns
conditions:
  - name: robot alone
    people: false          # the participant watches: claims and hand-overs are refused (default true)
    goals: [DC-3]          # a task (its own start), or {world: TASK, seed: N, goal: "literals or a sentence"}
  - name: in turns
    concurrent: false      # one step at a time, in plan order (default true: at once)
    goals: [{world: DC-3, seed: 12, goal: "put every block in the bin"}]
seed: 5                    # the start of a goal given as a task alone (default 0)
questionnaires: [nasa-tlx, sus]   # after each condition (default both)
```

The order is a balanced Latin square (Williams design): every condition comes first equally often, and follows
every other equally often (for an odd number of conditions, over the square and its mirror). A participant's row
is the number their ID ends in, less one (P01: row 0), else the ID's SHA-256; ``--row`` chooses it.
"""

from __future__ import annotations

import hashlib
import re
from dataclasses import dataclass
from pathlib import Path

from semgoal_bringup.study.questionnaires import QUESTIONNAIRES
from semgoal_core.tasks import TASKS

PARTICIPANT_ID = re.compile(r"[A-Za-z0-9_-]{1,32}")
"""A participant is known by this ID alone: letters, digits, ``_`` and ``-`` (it names their folder)."""


class ProtocolError(ValueError):
    """A protocol that cannot be run; the message says where and why."""


@dataclass(frozen=True)
class Episode:
    world: str
    """The task whose world (scene, blocks, start) the episode starts from."""
    seed: int
    goal: str
    """What is sent to the planner: the task's name, literals or a sentence."""


@dataclass(frozen=True)
class Condition:
    name: str
    episodes: tuple[Episode, ...]
    people: bool = True
    concurrent: bool = True

    @property
    def slug(self) -> str:
        """The condition's name as a file name."""
        return re.sub(r"[^a-z0-9]+", "-", self.name.lower()).strip("-") or "condition"


@dataclass(frozen=True)
class Protocol:
    name: str
    conditions: tuple[Condition, ...]
    questionnaires: tuple[str, ...]

    def order(self, row: int) -> list[int]:
        """The conditions' order (indices) in row ``row`` of the balanced Latin square."""
        rows = williams_square(len(self.conditions))
        return rows[row % len(rows)]


def williams_square(n: int) -> list[list[int]]:
    """A balanced Latin square of ``n`` conditions: rows 0, 1, n-1, 2, n-2, ... shifted by the row's number; for
    odd ``n`` followed by each row reversed, so that every condition follows every other equally often."""
    first = [0] + [(i + 1) // 2 if i % 2 else n - i // 2 for i in range(1, n)]
    rows = [[(c + r) % n for c in first] for r in range(n)]
    return rows + [row[::-1] for row in rows] if n % 2 else rows


def participant_row(participant: str) -> int:
    """The square's row of a participant: the number their ID ends in, less one, else from its SHA-256."""
    digits = re.search(r"(\d+)$", participant)
    if digits:
        return max(int(digits.group(1)) - 1, 0)
    return int.from_bytes(hashlib.sha256(participant.encode()).digest()[:4], "big")


def check_participant(participant: str) -> str:
    if not PARTICIPANT_ID.fullmatch(participant):
        raise ProtocolError(f"a participant ID is 1 to 32 letters, digits, '_' or '-', got {participant!r}")
    return participant


def load_protocol(path: Path) -> Protocol:
    """The protocol in ``path``; ProtocolError naming what is wrong."""
    import yaml

    try:
        data = yaml.safe_load(Path(path).read_text())
    except (OSError, yaml.YAMLError) as error:
        raise ProtocolError(f"cannot read the protocol {path}: {error}") from None
    return parse_protocol(data, str(path))


def parse_protocol(data: object, where: str = "the protocol") -> Protocol:
    if not isinstance(data, dict):
        raise ProtocolError(f"{where}: a mapping with name, conditions and questionnaires is needed")
    unknown = set(data) - {"name", "conditions", "seed", "questionnaires"}
    if unknown:
        raise ProtocolError(f"{where}: unknown key(s) {', '.join(sorted(map(str, unknown)))}")
    seed = _integer(data.get("seed", 0), f"{where}: seed")
    conditions = data.get("conditions")
    if not isinstance(conditions, list) or not conditions:
        raise ProtocolError(f"{where}: conditions must be a list of one or more")
    parsed = tuple(_condition(item, seed, f"{where}: condition {i + 1}") for i, item in enumerate(conditions))
    names = [c.name for c in parsed]
    if len(set(names)) != len(names) or len({c.slug for c in parsed}) != len(parsed):
        raise ProtocolError(f"{where}: condition names must differ (as file names too): {', '.join(names)}")
    questionnaires = data.get("questionnaires", list(QUESTIONNAIRES))
    if not isinstance(questionnaires, list) or not set(questionnaires) <= set(QUESTIONNAIRES):
        raise ProtocolError(f"{where}: questionnaires are a list of {', '.join(QUESTIONNAIRES)}, got {questionnaires!r}")
    return Protocol(str(data.get("name", "study")), parsed, tuple(questionnaires))


def _condition(item: object, seed: int, where: str) -> Condition:
    if not isinstance(item, dict) or not isinstance(item.get("name"), str) or not item["name"].strip():
        raise ProtocolError(f"{where}: a mapping with a name and goals is needed")
    unknown = set(item) - {"name", "goals", "people", "concurrent"}
    if unknown:
        raise ProtocolError(f"{where}: unknown key(s) {', '.join(sorted(map(str, unknown)))}")
    goals = item.get("goals")
    if not isinstance(goals, list) or not goals:
        raise ProtocolError(f"{where} ({item['name']}): goals must be a list of one or more")
    flags = {}
    for flag in ("people", "concurrent"):
        value = item.get(flag, True)
        if not isinstance(value, bool):
            raise ProtocolError(f"{where} ({item['name']}): {flag} is true or false, got {value!r}")
        flags[flag] = value
    episodes = tuple(_episode(goal, seed, f"{where} ({item['name']}), goal {j + 1}") for j, goal in enumerate(goals))
    return Condition(item["name"].strip(), episodes, **flags)


def _episode(goal: object, seed: int, where: str) -> Episode:
    if isinstance(goal, str):
        goal = {"world": goal, "goal": goal}
    if not isinstance(goal, dict) or set(goal) - {"world", "seed", "goal"} or "world" not in goal:
        raise ProtocolError(f"{where}: a task name, or {{world: TASK, seed: N, goal: TEXT}}")
    world = str(goal["world"])
    if world not in TASKS:
        raise ProtocolError(f"{where}: unknown task {world!r} (tasks: {', '.join(TASKS)})")
    text = str(goal.get("goal", world)).strip()
    if not text:
        raise ProtocolError(f"{where}: the goal is empty")
    return Episode(world, _integer(goal.get("seed", seed), f"{where}: seed"), text)


def _integer(value: object, where: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value < 2**63:
        raise ProtocolError(f"{where} must be a whole number from 0, got {value!r}")
    return value
