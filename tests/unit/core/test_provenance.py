"""Provenance names this checkout's commit and the libraries' installed versions."""

import subprocess
from pathlib import Path

import pytest

from semgoal_core.provenance import LIBRARIES, UNKNOWN, describe, git_state, provenance, traced

ROOT = Path(__file__).parents[3]


@pytest.mark.slow
def test_the_record_names_this_checkout_and_the_versions() -> None:
    record = provenance("./semgoal eval --tasks MC-2", seed=7, root=ROOT)
    head = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    assert record["commit"] == head and isinstance(record["dirty"], bool)
    assert set(record["versions"]) == set(LIBRARIES) and record["versions"]["numpy"] != UNKNOWN
    assert record["command"] == "./semgoal eval --tasks MC-2" and record["seed"] == 7
    line = describe(record)
    assert line.startswith(f"commit {head[:12]} (") and "numpy " in line and "seed 7" in line


@pytest.mark.slow
def test_outside_a_checkout_the_commit_is_unknown(tmp_path: Path) -> None:
    assert git_state(tmp_path) == (UNKNOWN, None)
    assert "no git checkout" in describe(provenance("x", root=tmp_path))


def _git(repo: Path, *args: str) -> str:
    return subprocess.run(["git", "-C", str(repo), *args], capture_output=True, text=True, check=True).stdout.strip()


@pytest.mark.slow
def test_results_written_into_runs_or_results_and_prose_do_not_make_the_code_dirty(tmp_path: Path) -> None:
    _git(tmp_path, "init", "-q")
    _git(tmp_path, "config", "user.email", "t@example.org")
    _git(tmp_path, "config", "user.name", "t")
    for path in ("runs/seed1/progress.csv", "results/table1.md", "README.md", "docs/notes.md", "src/code.py"):
        (tmp_path / path).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / path).write_text("before\n")
    _git(tmp_path, "add", ".")
    _git(tmp_path, "commit", "-qm", "start")
    (tmp_path / "runs/seed1/progress.csv").write_text("a training row\n")
    (tmp_path / "results/table1.md").write_text("a new table\n")
    (tmp_path / "README.md").write_text("the new figures\n")
    (tmp_path / "docs/notes.md").write_text("what they mean\n")
    assert git_state(tmp_path)[1] is False
    (tmp_path / "src/code.py").write_text("changed\n")
    assert git_state(tmp_path)[1] is True


@pytest.mark.slow
def test_a_file_made_before_records_were_kept_is_traced_to_the_first_commit_that_held_it(tmp_path: Path) -> None:
    _git(tmp_path, "init", "-q")
    _git(tmp_path, "config", "user.email", "t@example.org")
    _git(tmp_path, "config", "user.name", "t")
    (tmp_path / "requirements").mkdir()
    (tmp_path / "requirements" / "lock.txt").write_text("# pins\nnumpy==1.2.3\ntorch==9.9\n")
    (tmp_path / "actor.pt").write_bytes(b"weights")
    _git(tmp_path, "add", ".")
    _git(tmp_path, "commit", "-qm", "ship")
    first = _git(tmp_path, "rev-parse", "HEAD")
    (tmp_path / "requirements" / "lock.txt").write_text("numpy==2.0\n")
    (tmp_path / "moved").mkdir()
    _git(tmp_path, "mv", "actor.pt", "moved/actor.pt")
    _git(tmp_path, "commit", "-qam", "move and bump")
    record = traced(tmp_path / "moved" / "actor.pt", "./semgoal train --seed 5", 5, root=tmp_path)
    assert record["commit"] == first and record["dirty"] is None and record["seed"] == 5
    assert record["versions"]["numpy"] == "1.2.3" and record["versions"]["torch"] == "9.9"
    assert record["versions"]["mujoco"] == UNKNOWN
    assert "traced in git history" in describe(record)
    (tmp_path / "new.pt").write_bytes(b"never committed")
    assert traced(tmp_path / "new.pt", "x", None, root=tmp_path) is None


def test_every_shipped_actor_names_its_commit_and_versions() -> None:
    import json

    actors = sorted((ROOT / "src" / "semgoal_policy" / "models").rglob("actor.json"))
    assert len(actors) >= 9
    for path in actors:
        record = json.loads(path.read_text()).get("provenance")
        assert record, f"{path}: no provenance (./semgoal model-card --trace {path.parent})"
        assert len(record["commit"]) == 40 and all(record["versions"][name] != UNKNOWN for name in LIBRARIES), path
