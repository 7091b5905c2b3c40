"""bench-policy: the inference worker times every shipped actor the way the policy node runs it; the whole
command runs at a tiny size."""

import json
import subprocess
import sys

import pytest

from conftest import ROOT
from semgoal_bench.learning import LEARNERS, learning_point
from semgoal_bench.policy import REFERENCE, TRAIN_CONFIGS, inference, our_config, train_configs
from semgoal_core.vocabulary import PAPER_SCENES


def test_bf16_is_timed_only_where_the_cpu_multiplies_it_in_hardware():
    assert train_configs(True) == (TRAIN_CONFIGS, {})
    configs, left_out = train_configs(False)
    assert set(left_out) == {"ours:1:bf16", "ours:1:bf16:no-cloning"}
    assert all("hardware" in reason for reason in left_out.values())
    assert set(configs) | set(left_out) == set(TRAIN_CONFIGS) and REFERENCE in configs


def test_our_configurations_are_read_from_their_names():
    shipped, one = our_config("shipped", warmup=100), our_config("1:bf16:no-cloning", warmup=100)
    assert shipped.updates_per_step < 1.0 and shipped.sac.bc_weight > 0 and shipped.sac.precision == "fp32"
    assert one.updates_per_step == 1.0 and one.sac.bc_weight == 0.0 and one.sac.precision == "bf16"
    assert one.learning_starts == 100 and one.run_dir is None
    for wrong in ("2", "1:bf16:cloning", "1:bf16:no-cloning:more"):
        with pytest.raises(ValueError, match="not a configuration of ours"):
            our_config(wrong, warmup=100)


def test_inference_times_each_scenes_controller_and_the_peers():
    figures = inference(calls=20)
    expected = {"ours:Actor.act", "sb3:policy.predict", *(f"ours:SubgoalController.act[{s}]" for s in PAPER_SCENES)}
    assert set(figures) == expected
    for name, row in figures.items():
        assert 0 < row["p50_ms"] <= row["p99_ms"], name


@pytest.mark.slow
def test_bench_policy_runs_every_configuration_at_a_tiny_size():
    """The whole command, SB3's HER on our env included, so that it cannot break silently again."""
    result = subprocess.run([sys.executable, "-m", "semgoal_bench.policy", "--steps", "20", "--warmup", "110",
                             "--repeats", "1", "--calls", "5", "--json"],
                            capture_output=True, text=True, cwd=ROOT, timeout=280)
    assert result.returncode == 0, result.stderr[-3000:]
    figures = json.loads(result.stdout.strip().splitlines()[-1])
    training = figures["training"]
    rates = training["steps_per_second"]
    assert set(rates) == set(train_configs(training["bf16_native"])[0]) and all(rate > 0 for rate in rates.values())
    assert set(rates) | set(training["not_measured"]) == set(TRAIN_CONFIGS)
    assert training["ratio_to_reference"][REFERENCE] == 1.0


def test_a_learning_point_pools_the_types_with_a_wilson_interval():
    point = learning_point(4000, {"pick": 0.5, "put_near": 1.0}, episodes=10)
    assert point["overall"] == 0.75 and point["env_steps"] == 4000
    low, high = point["wilson_95"]
    assert 0.5 < low < 0.75 < high < 0.95


@pytest.mark.slow
def test_bench_policy_compares_learning_curves_at_a_tiny_size(tmp_path):
    """Ours and SB3 trained side by side and evaluated the same way, every few hundred steps."""
    figure = tmp_path / "curves.png"
    result = subprocess.run([sys.executable, "-m", "semgoal_bench.policy", "--learning", "800", "--eval-every", "400",
                             "--eval-episodes", "2", "--warmup", "110", "--figure", str(figure), "--json"],
                            capture_output=True, text=True, cwd=ROOT, timeout=280)
    assert result.returncode == 0, result.stderr[-3000:]
    curves = json.loads(result.stdout.strip().splitlines()[-1])["learning"]["curves"]
    assert set(curves) == set(LEARNERS)
    for points in curves.values():
        steps = [point["env_steps"] for point in points]
        assert len(steps) == 2 and steps == sorted(steps) and steps[-1] >= 800
        for point in points:
            assert set(point["success"]) == set(points[0]["success"]) and len(point["success"]) >= 4
            assert all(0.0 <= rate <= 1.0 for rate in point["success"].values())
    assert figure.stat().st_size > 10_000
