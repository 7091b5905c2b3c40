"""Provenance names this checkout's commit and the libraries' installed versions."""

import subprocess
from pathlib import Path

from semgoal_core.provenance import LIBRARIES, UNKNOWN, describe, git_state, provenance

ROOT = Path(__file__).parents[3]


def test_the_record_names_this_checkout_and_the_versions() -> None:
    record = provenance("./semgoal eval --tasks MC-2", seed=7, root=ROOT)
    head = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    assert record["commit"] == head and isinstance(record["dirty"], bool)
    assert set(record["versions"]) == set(LIBRARIES) and record["versions"]["numpy"] != UNKNOWN
    assert record["command"] == "./semgoal eval --tasks MC-2" and record["seed"] == 7
    line = describe(record)
    assert line.startswith(f"commit {head[:12]} (") and "numpy " in line and "seed 7" in line


def test_outside_a_checkout_the_commit_is_unknown(tmp_path: Path) -> None:
    assert git_state(tmp_path) == (UNKNOWN, None)
    assert "no git checkout" in describe(provenance("x", root=tmp_path))
