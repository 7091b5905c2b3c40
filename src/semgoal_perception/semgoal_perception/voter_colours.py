"""Which block colours a block voter tells apart, read without torch (the launch file and ``./semgoal up`` check a
task's blocks against the shipped voter before anything starts)."""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path

from semgoal_core.vocabulary import BLOCK_COLOURS


def colours_of(classes: int) -> tuple[str, ...]:
    """A voter's colours from its class count: no block, then the first ``classes - 1`` of ``BLOCK_COLOURS``."""
    return tuple(BLOCK_COLOURS)[: classes - 1]


def exported_colours(folder: Path) -> tuple[str, ...]:
    """The colours of the voter exported in ``folder`` (its ``voter.json``)."""
    return colours_of(json.loads((folder / "voter.json").read_text())["config"]["classes"])


def check_blocks(colours: Sequence[str], blocks: Sequence[str]) -> None:
    """ValueError naming the ``blocks`` a voter that knows ``colours`` cannot see."""
    if unknown := [block for block in blocks if block not in colours]:
        raise ValueError(f"the block voter knows {', '.join(colours)}, not {', '.join(unknown)}: train one that does "
                         "(./semgoal train perception)")
