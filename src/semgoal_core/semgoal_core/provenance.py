"""Where a figure came from: the git commit (and whether the tree had uncommitted changes), the versions of the
libraries that decide the numbers, the command and the seed. Every exported actor, results file and recording
carries it, so a figure can be traced to the code that produced it."""

from __future__ import annotations

import datetime
import importlib.metadata
import os
import subprocess
from pathlib import Path

LIBRARIES = ("mujoco", "torch", "numpy", "gymnasium", "rclpy")
"""The libraries whose versions change results: physics, learning, arrays, the env API, the ROS client."""
UNKNOWN = "unknown"
OUTPUTS = ("runs", "results")
"""Folders the commands write into (a run's progress, Table 1): a change there is a result, not a code change,
so it does not make the checkout dirty (a training run rewrites its own tracked progress.csv as it goes)."""
PROSE = "**/*.md"
"""Markdown (the README, docs/, model cards) cannot change a figure, so editing it does not make the checkout dirty
either: the docs are written while the figures they report are measured."""


def source_root() -> Path:
    """The checkout the code runs from: ``SEMGOAL_ROOT`` (tools/env.sh sets it), else this file's."""
    return Path(os.environ.get("SEMGOAL_ROOT") or Path(__file__).resolve().parent)


def git_state(root: Path | None = None) -> tuple[str, bool | None]:
    """(commit, dirty) of the checkout at ``root`` (dirty: tracked changes outside :data:`OUTPUTS` and :data:`PROSE`);
    (:data:`UNKNOWN`, None) outside one (a plain install)."""
    root = root or source_root()
    try:
        commit = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True,
                                check=True, timeout=10).stdout.strip()
        changes = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no", "--", ".",
                                  *(f":(exclude){folder}" for folder in OUTPUTS), f":(exclude,glob){PROSE}"],
                                 capture_output=True, text=True, check=True, timeout=30).stdout
    except (OSError, subprocess.SubprocessError):
        return UNKNOWN, None
    return commit, bool(changes.strip())


def versions() -> dict[str, str]:
    """The installed version of each of :data:`LIBRARIES` (without importing them)."""
    found = {}
    for name in LIBRARIES:
        try:
            found[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            found[name] = UNKNOWN
    return found


def provenance(command: str, seed: int | None = None, root: Path | None = None) -> dict:
    """The record a result carries: commit, dirty, versions, command, seed and when (UTC)."""
    commit, dirty = git_state(root)
    return {"commit": commit, "dirty": dirty, "versions": versions(), "command": command, "seed": seed,
            "created": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")}


LOCK_FILE = "requirements/lock.txt"


def traced(path: Path, command: str, seed: int | None, root: Path | None = None) -> dict | None:
    """The record of a file made before records were kept, traced in git history: the first commit that held
    exactly its content (what made it ran on that code or earlier), the library versions pinned in that
    commit's lock file, and that commit's date; None when git does not know the content."""
    root = root or source_root()
    try:
        blob = subprocess.run(["git", "-C", str(root), "hash-object", str(path)], capture_output=True, text=True,
                              check=True, timeout=30).stdout.strip()
        commits = subprocess.run(["git", "-C", str(root), "log", "--all", "--reverse", "--format=%H %cI",
                                  f"--find-object={blob}"], capture_output=True, text=True, check=True,
                                 timeout=120).stdout.split("\n")
        commit, created = commits[0].split()
        lock = subprocess.run(["git", "-C", str(root), "show", f"{commit}:{LOCK_FILE}"], capture_output=True,
                              text=True, timeout=30).stdout
    except (OSError, subprocess.SubprocessError, ValueError):
        return None
    pinned = dict(line.split("==", 1) for line in lock.splitlines() if "==" in line and not line.startswith("#"))
    return {"commit": commit, "dirty": None, "versions": {name: pinned.get(name, UNKNOWN) for name in LIBRARIES},
            "command": command, "seed": seed, "created": created,
            "traced": "from git history: the first commit that held this file; it was made with that code or "
                      "earlier, and the versions are those pinned there"}


def describe(record: dict) -> str:
    """One line for a results page: ``commit 1a2b3c4d5e6f (clean tree), mujoco 3.3.0, ..., seed 3000000``."""
    tree = {True: "with uncommitted changes", False: "clean tree", None: "no git checkout"}[record["dirty"]]
    if record.get("traced"):
        tree = "traced in git history: the first commit that held this file"
    libraries = ", ".join(f"{name} {version}" for name, version in record["versions"].items())
    seed = "" if record["seed"] is None else f", seed {record['seed']}"
    return f"commit {record['commit'][:12]} ({tree}), {libraries}{seed}, {record['created']}"
