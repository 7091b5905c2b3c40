"""Study mode's pure parts: the protocol and its counterbalanced order, the questionnaires' scores, Hoffman's
fluency measures from a plan's timeline, and a participant's session on disk."""

import json
from itertools import pairwise

import pytest

from semgoal_bringup.study.fluency import PlanSample, fluency
from semgoal_bringup.study.protocol import ProtocolError, parse_protocol, participant_row, williams_square
from semgoal_bringup.study.questionnaires import check_answers, score
from semgoal_bringup.study.session import Phase, StudySession

PROTOCOL = {"name": "desk", "seed": 4, "conditions": [
    {"name": "robot alone", "people": False, "goals": ["DC-2"]},
    {"name": "in turns", "concurrent": False, "goals": ["DC-3", {"world": "DC-2", "seed": 9, "goal": "put red in the bin"}]},
    {"name": "at once", "goals": ["DC-3"]}]}
TLX = {"mental": 30, "physical": 10, "temporal": 45, "performance": 20, "effort": 35, "frustration": 5}
SUS = {f"q{i}": 4 if i % 2 else 2 for i in range(1, 11)}


@pytest.mark.parametrize("n", [2, 3, 4, 5])
def test_the_order_is_a_balanced_latin_square(n: int) -> None:
    """Each condition comes at each place equally often, and follows each other condition equally often."""
    rows = williams_square(n)
    assert all(sorted(row) == list(range(n)) for row in rows)
    for place in range(n):
        assert len({row[place] for row in rows}) == n and len(rows) % n == 0
    follows = [(a, b) for row in rows for a, b in pairwise(row)]
    counts = {pair: follows.count(pair) for pair in set(follows)}
    assert len(counts) == n * (n - 1) and len(set(counts.values())) == 1


def test_a_participants_row_comes_from_their_id() -> None:
    assert [participant_row(p) for p in ("P01", "P02", "p17")] == [0, 1, 16]
    assert participant_row("alice") == participant_row("alice") >= 0


def test_a_protocol_is_read_and_its_mistakes_named() -> None:
    protocol = parse_protocol(PROTOCOL)
    assert [c.name for c in protocol.conditions] == ["robot alone", "in turns", "at once"]
    assert protocol.conditions[0].people is False and protocol.conditions[1].concurrent is False
    assert [(e.world, e.seed, e.goal) for e in protocol.conditions[1].episodes] == [
        ("DC-3", 4, "DC-3"), ("DC-2", 9, "put red in the bin")]
    assert protocol.questionnaires == ("nasa-tlx", "sus") and protocol.order(0) == [0, 1, 2]
    for broken, reason in [({"conditions": []}, "one or more"),
                           ({"conditions": [{"name": "a", "goals": ["XX-9"]}]}, "unknown task 'XX-9'"),
                           ({"conditions": [{"name": "a", "goals": ["DC-2"], "people": "yes"}]}, "people is true or false"),
                           ({"conditions": [{"name": "a", "goals": ["DC-2"]}, {"name": "A", "goals": ["DC-2"]}]}, "must differ"),
                           ({"conditions": [{"name": "a", "goals": ["DC-2"]}], "questionnaires": ["tlx"]}, "questionnaires"),
                           ({"conditions": [{"name": "a", "goals": [{"world": "DC-2", "seed": -1}]}]}, "whole number"),
                           ({"conditions": [{"name": "a", "goals": ["DC-2"], "colour": 1}]}, "unknown key")]:
        with pytest.raises(ProtocolError, match=reason):
            parse_protocol(broken)


def test_the_questionnaires_are_checked_and_scored() -> None:
    assert score("nasa-tlx", check_answers("nasa-tlx", TLX)) == pytest.approx(145 / 6)
    assert score("sus", check_answers("sus", SUS)) == 75.0
    assert score("sus", check_answers("sus", {f"q{i}": 5 if i % 2 else 1 for i in range(1, 11)})) == 100.0
    for name, answers, reason in [("sus", {**SUS, "q3": 6}, "q3 takes 1 to 5"), ("nasa-tlx", {**TLX, "mental": 33}, "steps of 5"),
                                  ("sus", {k: v for k, v in SUS.items() if k != "q9"}, "unanswered: q9"),
                                  ("sus", {**SUS, "q11": 3}, "unknown item"), ("sus", [], "a mapping"),
                                  ("nasa-tlx", {**TLX, "effort": True}, "effort takes")]:
        with pytest.raises(ValueError, match=reason):
            check_answers(name, answers)


def test_fluency_measures_share_the_working_time() -> None:
    """Robot alone 4 s, both 2 s, the person alone 2 s, neither 2 s; before and after, not working."""
    samples = [PlanSample(0.0, False, False, False), PlanSample(1.0, True, False, True), PlanSample(5.0, True, True, True),
               PlanSample(7.0, False, True, True), PlanSample(9.0, False, False, True), PlanSample(11.0, False, False, False),
               PlanSample(20.0, False, False, False)]
    measured = fluency(reversed(samples))
    assert measured.task_time == 10.0
    assert (measured.robot_idle, measured.human_idle, measured.concurrent_activity, measured.functional_delay) == \
        pytest.approx((0.4, 0.6, 0.2, 0.2))
    assert fluency([]).task_time == 0.0


def test_a_session_walks_the_order_keeps_the_answers_and_carries_on_after_a_restart(tmp_path) -> None:
    protocol = parse_protocol(PROTOCOL)
    session = StudySession(protocol, "P02", tmp_path)
    assert session.order == [1, 2, 0] and session.phase == Phase.READY
    with pytest.raises(ValueError, match="no questionnaire is asked now"):
        session.answer("sus", SUS)
    assert session.start().goal == "DC-3"
    assert session.recording_path().name == "1-in-turns-1.mcap"
    assert session.episode_ended(True, "ok", session.recording_path()).goal == "put red in the bin"
    assert session.episode_ended(False, "budget spent", None) is None and session.phase == Phase.QUESTIONNAIRE
    assert session.view()["questionnaires"][0]["name"] == "nasa-tlx"
    assert session.answer("nasa-tlx", TLX) == pytest.approx(145 / 6)
    with pytest.raises(ValueError, match="unanswered"):
        session.answer("sus", {"q1": 3})
    session.answer("sus", SUS)
    assert session.phase == Phase.READY and session.view()["condition"] == "at once"
    session.start()  # cut short: a console started again runs the condition from its start
    again = StudySession(protocol, "P02", tmp_path)
    assert (again.phase, again.view()["condition"], len(again.outcomes)) == (Phase.READY, "at once", 2)
    saved = json.loads((tmp_path / "P02" / "session.json").read_text())
    assert saved["order"] == ["in turns", "at once", "robot alone"] and saved["answers"][1]["score"] == 75.0
    assert (tmp_path / "P02" / "answers.csv").read_text().count("P02,in turns,") == 16
    with pytest.raises(ValueError, match="another protocol"):
        StudySession(parse_protocol({**PROTOCOL, "name": "other"}), "P02", tmp_path)
    with pytest.raises(ProtocolError, match="participant ID"):
        StudySession(protocol, "../etc", tmp_path)


def test_the_shipped_protocol_runs_every_condition_on_desk_goals() -> None:
    from semgoal_bringup.study.protocol import load_protocol
    from semgoal_ros.package_data import share_path

    protocol = load_protocol(share_path("semgoal_bringup", "study", "desk-together.yaml"))
    assert [(c.people, c.concurrent) for c in protocol.conditions] == [(False, True), (True, False), (True, True)]
    assert all(len(c.episodes) == 3 for c in protocol.conditions) and protocol.questionnaires == ("nasa-tlx", "sus")
