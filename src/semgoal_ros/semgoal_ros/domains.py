"""ROS domain ids for graphs that run side by side on one host (evaluations, demos, benchmarks, tests).

An id is held by an exclusive ``flock`` on ``$TMPDIR/semgoal-ros-domains/ID.lock`` for as long as its graph
runs: any number of graphs started through :func:`domain_for_this_process` get distinct ids, and a holder
that dies (even killed) frees its id at once, since the kernel drops its locks."""

from __future__ import annotations

import fcntl
import os
import random
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO

DOMAINS = range(1, 102)
"""Ids whose DDS ports stay below Linux's ephemeral range (ROS 2 docs, "The ROS_DOMAIN_ID": 0-101 are safe)."""
LOCK_DIR = Path(tempfile.gettempdir()) / "semgoal-ros-domains"


class NoFreeDomainError(RuntimeError):
    """Every id of :data:`DOMAINS` is held by a running graph."""


def lease(avoid: set[int] | frozenset[int] = frozenset(), lock_dir: Path = LOCK_DIR) -> tuple[int, IO]:
    """A free id, from a random place in :data:`DOMAINS` on (never one of ``avoid``), and the open lock file
    that holds it until it is closed."""
    lock_dir.mkdir(parents=True, exist_ok=True)
    start = random.randrange(len(DOMAINS))
    for k in range(len(DOMAINS)):
        domain = DOMAINS[(start + k) % len(DOMAINS)]
        if domain in avoid:
            continue
        handle = (lock_dir / f"{domain}.lock").open("a")
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            handle.close()
            continue
        return domain, handle
    raise NoFreeDomainError(f"every ROS domain id in {DOMAINS.start}-{DOMAINS.stop - 1} is held by a running "
                            f"graph (locks in {lock_dir}): stop one")


@contextmanager
def domain_for_this_process() -> Iterator[int]:
    """Hold a free id and make it this process's ``ROS_DOMAIN_ID`` (and so that of the nodes it starts) while
    the block runs. The id in force before (an operator's, or the last graph's, whose participants may still
    be going away) is never chosen."""
    current = os.environ.get("ROS_DOMAIN_ID", "")
    domain, handle = lease({int(current)} if current.isdigit() else set())
    os.environ["ROS_DOMAIN_ID"] = str(domain)
    try:
        yield domain
    finally:
        handle.close()
