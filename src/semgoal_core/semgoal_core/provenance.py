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


def source_root() -> Path:
    """The checkout the code runs from: ``SEMGOAL_ROOT`` (tools/env.sh sets it), else this file's."""
    return Path(os.environ.get("SEMGOAL_ROOT") or Path(__file__).resolve().parent)


def git_state(root: Path | None = None) -> tuple[str, bool | None]:
    """(commit, dirty) of the checkout at ``root``; (:data:`UNKNOWN`, None) outside one (a plain install)."""
    root = root or source_root()
    try:
        commit = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True,
                                check=True, timeout=10).stdout.strip()
        changes = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"],
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


def describe(record: dict) -> str:
    """One line for a results page: ``commit 1a2b3c4d5e6f (clean tree), mujoco 3.3.0, ..., seed 3000000``."""
    tree = {True: "with uncommitted changes", False: "clean tree", None: "no git checkout"}[record["dirty"]]
    libraries = ", ".join(f"{name} {version}" for name, version in record["versions"].items())
    seed = "" if record["seed"] is None else f", seed {record['seed']}"
    return f"commit {record['commit'][:12]} ({tree}), {libraries}{seed}, {record['created']}"
