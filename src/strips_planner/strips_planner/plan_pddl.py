"""`./semgoal plan-pddl DOMAIN PROBLEM [--search S] [--heuristic H] [--time-limit T] [--stats]`: our planner on any
STRIPS PDDL, and ADL's conditions, conditional effects and derived predicates.

Exit 0 with the plan (one action a line, then ``; cost = N`` where the problem minimises total-cost), 1
unsolvable, 2 bad PDDL, an unreadable file or a bad command line, 3 valid PDDL outside the supported fragment
(the message names the construct), 4 no plan within the time limit.

The command starts in a bare interpreter (see ./semgoal), and it reads its few arguments by hand: argparse,
with the gettext, locale and shutil it loads, would be about a tenth of its whole start-up.
"""

from __future__ import annotations

import sys

from strips_planner.heuristics import HEURISTICS
from strips_planner.pddl import PddlError, PddlUnsupportedError
from strips_planner.planner import check_choice, solve_pddl
from strips_planner.search import SEARCHES

USAGE = (f"usage: semgoal plan-pddl DOMAIN PROBLEM [--search {{{','.join(SEARCHES)}}}] "
         f"[--heuristic {{{','.join(HEURISTICS)}}}[+...]] [--time-limit SECONDS] [--stats]")
HELP = f"""{USAGE}

Plan with our STRIPS planner (:strips :typing :negative-preconditions :equality :action-costs, constants,
either types; or, imply, forall and exists in preconditions and goals; when and forall in effects; :derived).

options:
  --search S      bfs (default, shortest plans), astar (shortest plans with an admissible heuristic),
                  gbfs (greedy best-first: fast, not shortest), lazy (greedy best-first evaluating a
                  state only when it expands it: faster where states have many successors); with
                  (:metric minimize (total-cost)), shortest means cheapest and bfs searches by cost
                  (uniform-cost), while the greedy ones are guided as if every action cost 1 (as
                  LAMA's first iteration) and print the plan's real cost
  --heuristic H   default: blind (bfs), lmcut (astar; hmax where the task has conditional effects, which
                  lmcut does not take), hff (gbfs), hff+lmcount (lazy); the greedy searches
                  take several joined by '+', one open list each, in turn; lmcount (the landmark
                  count) guides only them
  --time-limit T  give up after T seconds (exit 4), looked at in Python's steps, every 65,536 join
                  steps of grounding's exploration and every 256 expansions of the search; default: none
  --stats         print expanded and generated states and the search time to stderr

exit: 0 plan, 1 unsolvable, 2 bad PDDL / unreadable file / bad arguments, 3 unsupported PDDL, 4 no plan
      within the time limit"""


class UsageError(ValueError):
    """A command line that names no task or an unknown option; the message says which."""


class TimeLimitError(Exception):
    """The time limit ran out (raised by the alarm's handler, inside the search's periodic signal check)."""


def parse_arguments(argv: list[str]) -> tuple[str, str, str, str | None, bool, float | None]:
    """(domain, problem, search, heuristic or None for the search's default, stats, time limit or None) from the
    command line."""
    files: list[str] = []
    options: dict[str, str | None] = {"--search": "bfs", "--heuristic": None, "--time-limit": None}
    stats = False
    arguments = iter(argv)
    for argument in arguments:
        name, equals, value = argument.partition("=")
        if argument == "--stats":
            stats = True
        elif name in options:
            value = value if equals else next(arguments, None)
            if value is None:
                raise UsageError(f"{name} needs a value")
            options[name] = value
        elif argument.startswith("-") and argument != "-":
            raise UsageError(f"unknown option {argument!r}")
        else:
            files.append(argument)
    if len(files) != 2:
        raise UsageError(f"give a DOMAIN and a PROBLEM file, not {len(files)} file(s)")
    try:
        check_choice(options["--search"], options["--heuristic"])
    except ValueError as error:
        raise UsageError(str(error)) from None
    return files[0], files[1], options["--search"], options["--heuristic"], stats, _seconds(options["--time-limit"])


def _seconds(text: str | None) -> float | None:
    if text is None:
        return None
    try:
        seconds = float(text)
    except ValueError:
        seconds = float("nan")
    if not 0 < seconds < 10**7:  # NaN fails too
        raise UsageError(f"--time-limit takes a positive number of seconds, not {text!r}")
    return seconds


def main(argv: list[str]) -> int:
    if "-h" in argv or "--help" in argv:
        print(HELP)
        return 0
    try:
        domain, problem, search, heuristic, stats, limit = parse_arguments(argv)
    except UsageError as error:
        print(f"{USAGE}\nsemgoal plan-pddl: {error}", file=sys.stderr)
        return 2
    try:
        with _Alarm(limit):
            result = solve_pddl(_read(domain), _read(problem), search, heuristic)
    except TimeLimitError:
        print(f"semgoal plan-pddl: no plan within the time limit of {limit:g} s", file=sys.stderr)
        return 4
    except OSError as error:
        print(f"semgoal plan-pddl: {error}", file=sys.stderr)
        return 2
    except PddlUnsupportedError as error:
        print(f"semgoal plan-pddl: unsupported PDDL: {error}", file=sys.stderr)
        return 3
    except PddlError as error:
        print(f"semgoal plan-pddl: bad PDDL: {error}", file=sys.stderr)
        return 2
    for warning in result.warnings:
        print(f"semgoal plan-pddl: warning: {warning}", file=sys.stderr)
    if stats:
        print(f"expanded {result.stats.expanded}, generated {result.stats.generated}, "
              f"{result.seconds * 1000:.2f} ms", file=sys.stderr)
    if result.plan is None:
        print("unsolvable")
        if result.reason:
            print(result.reason, file=sys.stderr)
        return 1
    print("\n".join(map(str, result.plan)) if result.plan else "; the goal holds in the initial state: an empty plan")
    if result.cost is not None:
        print(f"; cost = {result.cost}")
    return 0


class _Alarm:
    """Raise :class:`TimeLimitError` in this thread after ``seconds`` (None: never); the searches check for signals
    every few hundred expansions. An alarm set before (a test runner's timeout) gets its handler and the rest of its
    time back."""

    def __init__(self, seconds: float | None) -> None:
        self.seconds = seconds

    def __enter__(self) -> None:
        if self.seconds is not None:
            import signal
            import time

            def expire(*_) -> None:
                raise TimeLimitError

            self.previous = signal.signal(signal.SIGALRM, expire)
            self.previous_timer, self.started = signal.setitimer(signal.ITIMER_REAL, self.seconds), time.monotonic()

    def __exit__(self, *_) -> None:
        if self.seconds is not None:
            import signal
            import time

            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, self.previous)
            delay, interval = self.previous_timer
            if delay > 0:
                signal.setitimer(signal.ITIMER_REAL, max(delay - (time.monotonic() - self.started), 1e-3), interval)


def _read(path: str) -> str:
    """The file's text; PddlError where it is not UTF-8 (a binary file given by mistake)."""
    with open(path, "rb") as file:
        data = file.read()
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise PddlError(f"{path}: not UTF-8 text (byte 0x{data[error.start]:02x} at offset {error.start})") from None
