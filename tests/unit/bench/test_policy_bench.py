"""bench-policy's inference worker times every shipped actor the way the policy node runs it."""

from bench.policy import inference
from semgoal_core.vocabulary import SCENES


def test_inference_times_each_scenes_controller_and_the_peers():
    figures = inference(calls=20)
    expected = {"ours:Actor.act", "sb3:policy.predict", *(f"ours:SubgoalController.act[{s}]" for s in SCENES)}
    assert set(figures) == expected
    for name, row in figures.items():
        assert 0 < row["p50_ms"] <= row["p99_ms"], name
