"""Seeded random 4-operator blocksworld problems (the benchmark set and the tests' fuzzing ground)."""

from __future__ import annotations

import itertools
import random

from semgoal_ros.package_data import share_path

DOMAIN_PATH = share_path("semgoal_planner", "domains", "blocksworld.pddl")


def _random_towers(rng: random.Random, blocks: list[str]) -> list[list[str]]:
    towers: list[list[str]] = []
    for block in rng.sample(blocks, len(blocks)):
        if towers and rng.random() < 0.6:
            rng.choice(towers).append(block)
        else:
            towers.append([block])
    return towers


def _facts(towers: list[list[str]]) -> list[str]:
    facts = []
    for tower in towers:
        facts.append(f"(on-table {tower[0]})")
        facts += [f"(on {top} {below})" for below, top in itertools.pairwise(tower)]
        facts.append(f"(clear {tower[-1]})")
    return facts


def problem(n_blocks: int, seed: int) -> str:
    """A problem with random start and goal towers over ``n_blocks`` blocks (always solvable)."""
    rng = random.Random(seed)
    blocks = [f"b{i}" for i in range(1, n_blocks + 1)]
    start, goal = _random_towers(rng, blocks), _random_towers(rng, blocks)
    goal_facts = [f for f in _facts(goal) if f.startswith("(on ")] or ["(arm-empty)"]
    return (f"(define (problem bw-{n_blocks}-{seed}) (:domain blocksworld)\n"
            f"  (:objects {' '.join(blocks)})\n"
            f"  (:init (arm-empty) {' '.join(_facts(start))})\n"
            f"  (:goal (and {' '.join(goal_facts)})))\n")
