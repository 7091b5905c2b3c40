"""What the collaboration console shows and does, without ROS or the web: the semantic state as sentences,
where a person's "put it there" puts a block, and the study log."""

from __future__ import annotations

import csv
import time
from collections.abc import Iterable, Mapping
from pathlib import Path

import numpy as np

from semgoal_core.geometry import MIN_CENTRE_DISTANCE, TABLE_CENTER, TABLE_HALF_SIZE, TABLE_TOP, bin_spot, clear_of, nearest
from semgoal_core.names import StepStatus, is_person
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, ONE_AGENT_REGIONS, THRESHOLDS, BinGeometry, SubGoal

SENTENCES = {"close": "{0} is near {1}", "above": "{0} is on {1}", "holding": "the robot holds {0}",
             "in_bin": "{0} is in the bin"}
"""How each predicate reads when it holds."""

UNSURE = 0.9
"""A literal the perception is less sure of than this (the share of its position samples that agree) is shown
as unsure."""


def unsure_sentences(literals: Iterable[tuple[str, tuple[str, ...], bool, float]], below: float = UNSURE) -> list[str]:
    """The literals (predicate, arguments, value, confidence) the camera's perception is unsure of, as
    sentences of what it takes to be the case and how sure it is; a symmetric pair reads once."""
    seen, lines = set(), []
    for name, args, value, confidence in literals:
        key = (name, tuple(sorted(args))) if name == "close" else (name, tuple(args))
        if confidence >= below or key in seen or name not in SENTENCES:
            continue
        seen.add(key)
        sentence = SENTENCES[name].format(*args)
        lines.append(f"{sentence if value else 'not: ' + sentence}? ({confidence:.0%} sure)")
    return lines


PLACES = ("bin", "table", "near", "on")
"""Where a person can put a block: in the bin, on a free spot of the table, next to or on another block."""
NEAR_DISTANCE = 0.065
"""Centre distance (m) of a block put next to another: touching-close (under ``close``'s 0.10), clear of it."""
TABLE_MARGIN = 0.06
"""Spots on the table keep this far (m) inside its edges."""
GRID_STEP = 0.02

LOG_FIELDS = ("wall_time", "sim_time", "who", "event", "detail", "outcome")
STEP_PLACES = {"put_in_bin": "bin", "put_on_table": "table", "put_away": "table", "put_near": "near", "put_on": "on"}
"""The console's place for each type of step a person does: a put away is put on a free spot of the table, away from
every other block."""


def step_place(subgoal: SubGoal) -> tuple[str, str]:
    """Where a person's step puts its block through the console: the place and its other block ("" for none)."""
    place = STEP_PLACES[subgoal.kind]
    return place, subgoal.references[0] if place in ("near", "on") else ""


def region_taken(place: str, steps: Iterable[tuple[str, str, str]]) -> str:
    """Why a person may not put a block at ``place`` now ("" when they may): a robot's active step is at it. ``steps``:
    the plan's (action, assignee, status)."""
    for action, assignee, status in steps:
        kind = action.split("(")[0]
        if status == StepStatus.ACTIVE and not is_person(assignee) and ONE_AGENT_REGIONS.get(kind) == place:
            return f"the {assignee} is putting a block in the {place} ({action}): wait until it is done"
    return ""


def sentences(true_literals: Iterable[tuple[str, tuple[str, ...]]]) -> list[str]:
    """The literals that hold (predicate, arguments), as sentences; a symmetric pair reads once."""
    seen, lines = set(), []
    for name, args in true_literals:
        key = (name, tuple(sorted(args))) if name == "close" else (name, tuple(args))
        if key in seen or name not in SENTENCES:
            continue
        seen.add(key)
        lines.append(SENTENCES[name].format(*args))
    return lines


def place_position(place: str, block: str, blocks: Mapping[str, np.ndarray], bin_geometry: BinGeometry | None,
                   other: str = "") -> np.ndarray:
    """The centre (x, y, z) to put ``block`` at for ``place`` (:data:`PLACES`; ``other`` names the block of
    "near" / "on"); ValueError with the reason when there is no such place."""
    if block not in blocks:
        raise ValueError(f"there is no {block} block here (blocks: {', '.join(blocks)})")
    others = {name: np.asarray(p, dtype=float) for name, p in blocks.items() if name != block}
    here = np.asarray(blocks[block], dtype=float)
    resting = TABLE_TOP + BLOCK_HALF_SIZE
    if place == "bin":
        if bin_geometry is None:
            raise ValueError("this scene has no bin")
        spot = bin_spot(bin_geometry, list(others.values()), here)
        if spot is None:
            raise ValueError("the bin is full")
        return np.array([spot[0], spot[1], resting + bin_geometry.floor_thickness])
    if place in ("near", "on"):
        if other not in others:
            raise ValueError(f"put {block} {place} which block? one of {', '.join(others) or 'none'}")
        target = others[other]
        if place == "on":
            return np.array([target[0], target[1], target[2] + 2 * BLOCK_HALF_SIZE + 0.002])
        angles = np.linspace(0, 2 * np.pi, 16, endpoint=False)
        candidates = target[:2] + NEAR_DISTANCE * np.stack([np.cos(angles), np.sin(angles)], axis=1)
        obstacles = [p for name, p in others.items() if name != other]
        ok = _on_free_table(candidates, bin_geometry) & clear_of(candidates, obstacles) \
            & (np.linalg.norm(candidates - target[:2], axis=1) >= MIN_CENTRE_DISTANCE)
        spot = nearest(candidates, ok, here)
        if spot is None:
            raise ValueError(f"no free spot next to {other}")
        return np.array([spot[0], spot[1], target[2]])
    if place == "table":
        xs = np.arange(TABLE_CENTER[0] - TABLE_HALF_SIZE[0] + TABLE_MARGIN, TABLE_CENTER[0] + TABLE_HALF_SIZE[0] - TABLE_MARGIN, GRID_STEP)
        ys = np.arange(TABLE_CENTER[1] - TABLE_HALF_SIZE[1] + TABLE_MARGIN, TABLE_CENTER[1] + TABLE_HALF_SIZE[1] - TABLE_MARGIN, GRID_STEP)
        candidates = np.stack(np.meshgrid(xs, ys), axis=-1).reshape(-1, 2)
        away = clear_of(candidates, list(others.values()), clearance=THRESHOLDS.close_distance + 0.02)
        spot = nearest(candidates, _on_free_table(candidates, bin_geometry) & away, here)
        if spot is None:
            raise ValueError("no free spot on the table away from the other blocks")
        return np.array([spot[0], spot[1], resting])
    raise ValueError(f"unknown place {place!r}: one of {', '.join(PLACES)}")


def _on_free_table(candidates: np.ndarray, bin_geometry: BinGeometry | None) -> np.ndarray:
    """Candidates (M, 2) on the table, inside its margin and clear of the bin's outside."""
    inside = np.all(np.abs(candidates - np.asarray(TABLE_CENTER)) <= np.asarray(TABLE_HALF_SIZE) - TABLE_MARGIN, axis=1)
    if bin_geometry is None:
        return inside
    outer = np.asarray(bin_geometry.inner_half_size) + bin_geometry.wall_thickness + BLOCK_HALF_SIZE + 0.01
    return inside & np.any(np.abs(candidates - np.asarray(bin_geometry.center)) > outer, axis=1)


class StudyLog:
    """One study session's CSV: a row per action of the person and per change of the plan, in order, with
    wall time (s since the epoch) and sim time (s); flushed per row, so a crash loses nothing."""

    def __init__(self, path: Path) -> None:
        self.path = path
        path.parent.mkdir(parents=True, exist_ok=True)
        self._file = path.open("w", newline="")
        self._writer = csv.writer(self._file)
        self._writer.writerow(LOG_FIELDS)
        self._file.flush()

    def write(self, sim_time: float, who: str, event: str, detail: str, outcome: str = "") -> None:
        self._writer.writerow([f"{time.time():.3f}", f"{sim_time:.2f}", who, event, detail, outcome])
        self._file.flush()

    def close(self) -> None:
        self._file.close()
