"""The questionnaires asked after each condition, and their scores.

- ``nasa-tlx``: the raw NASA Task Load Index (Hart and Staveland, 1988; raw, unweighted, as in Hart, 2006): six
  scales from 0 to 100 in steps of 5; the score is their mean. Performance runs from 0, perfect, to 100, failure.
- ``sus``: the System Usability Scale (Brooke, 1996): ten statements rated 1 (strongly disagree) to 5 (strongly
  agree); the score is 2.5 times the sum of (rating - 1) over the odd statements and (5 - rating) over the even
  ones, from 0 to 100.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Questionnaire:
    title: str
    items: tuple[tuple[str, str], ...]
    """(key, question) in the order asked."""
    low: int
    high: int
    step: int
    anchors: tuple[str, str]
    """What the two ends of the scale mean."""


QUESTIONNAIRES = {
    "nasa-tlx": Questionnaire(
        "NASA Task Load Index (raw)",
        (("mental", "Mental demand: how mentally demanding was the task?"),
         ("physical", "Physical demand: how physically demanding was the task?"),
         ("temporal", "Temporal demand: how hurried or rushed was the pace of the task?"),
         ("performance", "Performance: how successful were you in accomplishing what you were asked to do?"),
         ("effort", "Effort: how hard did you have to work to accomplish your level of performance?"),
         ("frustration", "Frustration: how insecure, discouraged, irritated, stressed and annoyed were you?")),
        0, 100, 5, ("very low (performance: perfect)", "very high (performance: failure)")),
    "sus": Questionnaire(
        "System Usability Scale",
        (("q1", "I think that I would like to use this system frequently."),
         ("q2", "I found the system unnecessarily complex."),
         ("q3", "I thought the system was easy to use."),
         ("q4", "I think that I would need the support of a technical person to be able to use this system."),
         ("q5", "I found the various functions in this system were well integrated."),
         ("q6", "I thought there was too much inconsistency in this system."),
         ("q7", "I would imagine that most people would learn to use this system very quickly."),
         ("q8", "I found the system very cumbersome to use."),
         ("q9", "I felt very confident using the system."),
         ("q10", "I needed to learn a lot of things before I could get going with this system.")),
        1, 5, 1, ("strongly disagree", "strongly agree")),
}


def check_answers(name: str, answers: object) -> dict[str, int]:
    """The answers to questionnaire ``name`` as {item: value}; ValueError naming a missing, unknown or out-of-scale
    one."""
    if name not in QUESTIONNAIRES:
        raise ValueError(f"unknown questionnaire {name!r}: one of {', '.join(QUESTIONNAIRES)}")
    form = QUESTIONNAIRES[name]
    if not isinstance(answers, dict):
        raise ValueError(f"{name}: the answers are a mapping of item to value")
    keys = [key for key, _ in form.items]
    if missing := [key for key in keys if key not in answers]:
        raise ValueError(f"{name}: unanswered: {', '.join(missing)}")
    if unknown := sorted(set(map(str, answers)) - set(keys)):
        raise ValueError(f"{name}: unknown item(s) {', '.join(unknown)}")
    checked = {}
    for key in keys:
        value = answers[key]
        if isinstance(value, bool) or not isinstance(value, int) or not form.low <= value <= form.high \
                or (value - form.low) % form.step:
            raise ValueError(f"{name}: {key} takes {form.low} to {form.high} in steps of {form.step}, got {value!r}")
        checked[key] = value
    return checked


def score(name: str, answers: dict[str, int]) -> float:
    """The questionnaire's score (raw TLX: the mean of the six scales; SUS: 0 to 100)."""
    if name == "nasa-tlx":
        return sum(answers.values()) / len(answers)
    odd = sum(answers[f"q{i}"] - 1 for i in range(1, 11, 2))
    even = sum(5 - answers[f"q{i}"] for i in range(2, 11, 2))
    return 2.5 * (odd + even)
