"""The command lines' number types: a value out of range is an argparse error with the reason."""

import argparse

import pytest

from semgoal_core.arguments import count, counts, names, natural, seconds


@pytest.mark.parametrize(("kind", "text", "value"), [
    (count, "3", 3), (natural, "0", 0), (seconds, "2.5", 2.5), (counts, "4,6,8", [4, 6, 8]),
    (names, "pick, put_near,", ["pick", "put_near"])])
def test_a_value_in_range_is_read(kind, text: str, value) -> None:
    assert kind(text) == value


@pytest.mark.parametrize(("kind", "text", "words"), [
    (count, "0", "at least 1, got '0'"), (count, "-2", "at least 1"), (count, "two", "at least 1, got 'two'"),
    (count, "1.5", "a whole number"), (natural, "-1", "at least 0, got '-1'"), (seconds, "0", "positive number"),
    (seconds, "nan", "positive number"), (seconds, "inf", "positive number"), (seconds, "-3", "positive number"),
    (counts, "4,x", "joined by commas, got '4,x'"), (counts, "", "joined by commas"),
    (names, " , ", "one or more names joined by commas")])
def test_a_value_out_of_range_is_refused_with_the_reason(kind, text: str, words: str) -> None:
    with pytest.raises(argparse.ArgumentTypeError, match=words):
        kind(text)
