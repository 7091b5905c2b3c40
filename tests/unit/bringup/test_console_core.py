"""The console's core: what holds as sentences, where a person's "put it there" lands (a place the
predicates then read as meant), and a study log that keeps every row in order."""

import csv

import numpy as np
import pytest

from semgoal_bringup.tools.console_core import StudyLog, place_position, sentences
from semgoal_core.geometry import TABLE_TOP
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, LAYOUTS, SCENES, THRESHOLDS, evaluate

DESK = SCENES["desk_cleanup"]
BLOCKS = {"red": np.array([1.2, 0.6, TABLE_TOP + BLOCK_HALF_SIZE]), "green": np.array([1.3, 0.65, TABLE_TOP + BLOCK_HALF_SIZE]),
          "blue": np.array([1.42, 0.55, TABLE_TOP + BLOCK_HALF_SIZE])}


def test_what_holds_reads_as_sentences_with_each_pair_once() -> None:
    assert sentences([("close", ("red", "green")), ("close", ("green", "red")), ("above", ("blue", "red")),
                      ("holding", ("green",)), ("in_bin", ("red",))]) == \
        ["red is near green", "blue is on red", "the robot holds green", "red is in the bin"]


def true_literals(scene: str, positions: dict[str, np.ndarray]) -> set[str]:
    layout, objects = LAYOUTS[scene], SCENES[scene].objects
    padded = np.zeros((len(objects), 3))
    present = np.zeros(len(objects), dtype=bool)
    for i, name in enumerate(objects):
        if name in positions:
            padded[i], present[i] = positions[name], True
    vector = evaluate(layout, padded, np.array([1.0, 0.3, 0.9]), 0.1, TABLE_TOP, present)
    return {f"{name}({','.join(args)})" for (name, args), value in zip(layout.atoms, vector, strict=True) if value}


@pytest.mark.parametrize(("scene", "place", "other", "expected", "unexpected"), [
    ("desk_cleanup", "bin", "", {"in_bin(red)"}, set()),
    ("desk_cleanup", "table", "", set(), {"in_bin(red)"}),
    ("three_blocks", "near", "blue", {"close(red,blue)"}, {"above(red,blue)"}),
    ("two_blocks", "on", "green", {"above(red,green)"}, set()),
    ("three_blocks", "table", "", set(), {"close(red,green)", "close(red,blue)"}),
])
def test_a_place_puts_the_block_where_the_predicates_read_it_as_meant(scene, place, other, expected, unexpected) -> None:
    moved = {**BLOCKS, "red": place_position(place, "red", BLOCKS, SCENES[scene].bin, other)}
    literals = true_literals(scene, moved)
    assert expected <= literals and not unexpected & literals, (place, moved["red"], literals)


def test_impossible_places_are_refused_with_the_reason() -> None:
    with pytest.raises(ValueError, match="no bin"):
        place_position("bin", "red", BLOCKS, None)
    with pytest.raises(ValueError, match="there is no yellow block"):
        place_position("table", "yellow", BLOCKS, DESK.bin)
    with pytest.raises(ValueError, match="which block"):
        place_position("on", "red", BLOCKS, DESK.bin, "purple")
    with pytest.raises(ValueError, match="unknown place"):
        place_position("shelf", "red", BLOCKS, DESK.bin)
    full = {f"b{i}": np.array([DESK.bin.center[0] - 0.12 + 0.08 * i, DESK.bin.center[1], 0.45]) for i in range(4)}
    with pytest.raises(ValueError, match="the bin is full"):
        place_position("bin", "red", {**full, "red": BLOCKS["red"]}, DESK.bin)
    assert THRESHOLDS.close_distance > 0.065  # "next to" is close by the predicates' measure


def test_the_study_log_keeps_every_row_in_order(tmp_path) -> None:
    log = StudyLog(tmp_path / "logs" / "session.csv")
    log.write(1.5, "person", "goal", '{"text": "DC-3"}', "ok: goal sent")
    log.write(2.0, "planner", "plan", "revision 1", "awaiting_approval")
    rows = list(csv.DictReader((tmp_path / "logs" / "session.csv").open()))  # readable before close: flushed
    assert [(r["who"], r["event"], r["sim_time"]) for r in rows] == [("person", "goal", "1.50"), ("planner", "plan", "2.00")]
    assert float(rows[0]["wall_time"]) <= float(rows[1]["wall_time"])
    log.close()


def test_literals_the_perception_is_unsure_of_read_as_questions_with_how_sure_it_is() -> None:
    from semgoal_bringup.tools.console_core import unsure_sentences

    literals = [("close", ("red", "green"), True, 0.62), ("close", ("green", "red"), True, 0.62),
                ("in_bin", ("red",), False, 0.7), ("above", ("red", "green"), False, 1.0)]
    assert unsure_sentences(literals) == ["red is near green? (62% sure)", "not: red is in the bin? (70% sure)"]


def test_the_camera_view_draws_each_estimate_where_it_projects() -> None:
    import numpy as np

    from semgoal_bringup.tools.perception_view import SCALE, draw_estimates
    from semgoal_perception.geometry import PinholeCamera

    down = np.array([[1.0, 0, 0, 1.3], [0, -1.0, 0, 0.75], [0, 0, -1.0, 1.4], [0, 0, 0, 1.0]])
    camera = PinholeCamera(140.0, 140.0, 79.5, 59.5, down)
    image = np.asarray(draw_estimates(np.full((120, 160, 3), 200, np.uint8), camera,
                                      [("red", np.array([1.3, 0.75, 0.4]), 0), ("green", np.full(3, np.nan), 4)]))
    assert image.shape == (120 * SCALE, 160 * SCALE, 3)
    u, v = (camera.project(np.array([[1.3, 0.75, 0.4]]))[0] + 0.5) * SCALE
    assert tuple(image[int(v), int(u)]) != (200, 200, 200)  # the cross is drawn on the estimate
    assert (image[:, :200] == 200).all()  # and nothing for the block never seen


def test_the_console_refuses_a_person_that_is_no_agent_before_it_starts(capsys) -> None:
    from semgoal_bringup.tools import console

    with pytest.raises(SystemExit) as stopped:
        console.main(["--person", "robot-arm"])
    assert stopped.value.code == 2 and "a named person 'human:NAME'" in capsys.readouterr().err
