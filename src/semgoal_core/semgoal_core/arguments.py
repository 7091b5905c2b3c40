"""argparse types for the numbers the command lines take: a value out of range is refused where it is read, with
the reason and exit 2, not met later as a traceback (a negative seed deep in numpy, no episodes in a mean)."""

from __future__ import annotations

import argparse
import math


def count(text: str) -> int:
    """A whole number of at least 1: episodes, steps, repeats, jobs, frames."""
    return _whole(text, 1)


def natural(text: str) -> int:
    """A whole number of at least 0: seeds (numpy's generators take no negative seed), control steps to linger."""
    return _whole(text, 0)


def seconds(text: str) -> float:
    """A positive, finite number of seconds: time limits."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"must be a positive number of seconds, got {text!r}")
    return value


def counts(text: str) -> list[int]:
    """Comma-separated whole numbers of at least 1 ('4,6,8')."""
    try:
        return [count(part) for part in text.split(",")]
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(f"must be whole numbers of at least 1 joined by commas, got {text!r}") from None


def names(text: str) -> list[str]:
    """Comma-separated names ('pick,put_near'), the spaces around each dropped; at least one."""
    parts = [part.strip() for part in text.split(",") if part.strip()]
    if not parts:
        raise argparse.ArgumentTypeError(f"must be one or more names joined by commas, got {text!r}")
    return parts


def _whole(text: str, least: int) -> int:
    try:
        value = int(text)
    except ValueError:
        value = least - 1
    if value < least:
        raise argparse.ArgumentTypeError(f"must be a whole number of at least {least}, got {text!r}")
    return value
