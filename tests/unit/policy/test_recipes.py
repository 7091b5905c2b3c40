"""Recipes as data: each shipped actor's configuration is its recipe's, and the train command builds its
configuration from defaults, then the recipe, then the flags."""

import dataclasses
import json

import pytest

from semgoal_bringup.experiments.training import checkout_models_dir, train_config, trainer_for
from semgoal_policy.actor import models_dir
from semgoal_policy.recipes import RUN_FIELDS, RecipeError, build_config, load_recipe, recipe_names
from semgoal_policy.sac import SacConfig
from semgoal_policy.trainer import PHASED_SETTINGS, PROJECT_ROOT, TrainConfig, schedule, settings_at

MODELS_DIR = models_dir()
SHIPPED = sorted(path.parent.name for path in MODELS_DIR.glob("*/actor.json"))


def _recipe_part(config: dict) -> dict:
    return {k: v for k, v in config.items() if k not in RUN_FIELDS}


def test_every_shipped_actor_has_a_recipe() -> None:
    assert SHIPPED and set(SHIPPED) <= set(recipe_names())


def _in_force_at(config: dict, env_steps: int) -> dict:
    """A recorded configuration's settings in force at ``env_steps`` (its phases applied), without the phases."""
    settled = {k: v for k, v in config.items() if k != "phases"}
    for phase in config.get("phases", ()):
        if phase["from_steps"] <= env_steps:
            settled.update(phase["settings"])
    return settled


@pytest.mark.parametrize("name", SHIPPED)
def test_the_recipe_reproduces_the_shipped_configuration_and_schedule(name: str) -> None:
    """The recipe gives the settings the actor ended with and the schedule it trained on, phase by phase (an
    actor that records no schedule trained on one setting throughout)."""
    shipped = json.loads((MODELS_DIR / name / "actor.json").read_text())
    config, _ = train_config(["--recipe", name, "--seed", str(shipped["seed"])])
    steps = shipped["env_steps"]
    rebuilt = _in_force_at(json.loads(json.dumps(dataclasses.asdict(config), default=str)), steps)
    recorded = _in_force_at(shipped["config"], steps)
    newer = rebuilt.keys() - recorded.keys()  # settings added after the actor trained: at the default it trained with
    defaults = {field.name: field.default for field in dataclasses.fields(TrainConfig)}
    assert all(rebuilt[key] == defaults[key] for key in newer), newer
    newer_sac = rebuilt["sac"].keys() - recorded["sac"].keys()
    sac_defaults = {field.name: field.default for field in dataclasses.fields(SacConfig)}
    assert all(rebuilt["sac"].pop(key) == sac_defaults[key] for key in newer_sac), newer_sac
    assert _recipe_part({k: v for k, v in rebuilt.items() if k in recorded}) == _recipe_part(recorded)
    assert rebuilt["seed"] == shipped["seed"]
    ran = shipped.get("schedule") or [{"from_steps": 0, **{k: recorded[k] for k in PHASED_SETTINGS if k in recorded}}]
    promised = schedule(config, until=steps)
    assert len(promised) == len(ran) and all({k: want[k] for k in got} == got for want, got in zip(promised, ran, strict=True)), \
        (promised, ran)


def test_a_phase_changes_its_settings_from_its_step_on(tmp_path) -> None:
    recipe = tmp_path / "phased.yaml"
    recipe.write_text("scene: three_blocks\nsteps: 300\nmissed_put_share: 0.0\n"
                      "phases:\n- from_steps: 200\n  missed_put_share: 0.25\n  demo_fraction: 0.5\n")
    config = build_config(load_recipe(str(recipe)), {})
    assert settings_at(config, 199).missed_put_share == 0.0 and settings_at(config, 200).missed_put_share == 0.25
    assert [row["from_steps"] for row in schedule(config)] == [0, 200]
    assert schedule(config)[1]["demo_fraction"] == 0.5 and schedule(config, until=200) == schedule(config)[:1]


@pytest.mark.parametrize("phases, reason", [
    ("- from_steps: 0\n  missed_put_share: 0.25\n", "positive whole number"),
    ("- from_steps: 100\n  lr: 0.1\n", "may set"),
    ("- from_steps: 200\n  demo_noise: 0.1\n- from_steps: 100\n  demo_noise: 0.3\n", "increasing"),
])
def test_a_bad_phase_is_refused_with_the_reason(tmp_path, phases: str, reason: str) -> None:
    recipe = tmp_path / "bad.yaml"
    recipe.write_text("scene: two_blocks\nphases:\n" + phases)
    with pytest.raises(RecipeError, match=reason):
        load_recipe(str(recipe))


def test_flags_override_the_recipe_and_the_recipe_overrides_the_defaults() -> None:
    config, args = train_config(["--recipe", "desk_cleanup", "--seed", "81", "--lr", "3e-4", "--no-snapshots",
                                 "--resume"])
    assert config.sac.lr == 3e-4 and not config.snapshots and args.resume
    assert config.derived_features == ("bin_target", "subject_offset") and config.sac.log_std_max == 0.0
    assert config.sac.actor_average_rate == load_recipe("desk_cleanup")["sac"]["actor_average_rate"]
    assert TrainConfig(scene="desk_cleanup").sac.log_std_max != 0.0  # the recipe's, not the default
    plain, _ = train_config(["--scene", "two_blocks", "--derive", "subject_offset", "--derive", "bin_target"])
    assert plain.derived_features == ("subject_offset", "bin_target") and plain.sac == TrainConfig("x").sac


@pytest.mark.parametrize("argv, reason", [
    (["--recipe", "kitchen"], "no recipe 'kitchen'"),
    (["--recipe", "desk_cleanup", "--scene", "two_blocks"], "is for scene desk_cleanup"),
    (["--seed", "3"], "give a --recipe or a --scene"),
    (["--scene", "kitchen"], "scenes are"),
    (["--recipe", "desk_cleanup", "--ship", "--export-dir", "x"], "leave out --export-dir"),
    (["--scene", "two_blocks", "--lr", "fast"], "invalid float value"),
])
def test_bad_train_arguments_are_refused_with_the_reason(argv, reason, capsys) -> None:
    with pytest.raises(SystemExit) as exit_info:
        train_config(argv)
    assert exit_info.value.code == 2 and reason in capsys.readouterr().err


def test_a_recipe_with_an_unknown_setting_is_refused(tmp_path) -> None:
    path = tmp_path / "typo.yaml"
    path.write_text("scene: two_blocks\nlearning_rate: 0.1\n")
    with pytest.raises(RecipeError, match="unknown settings learning_rate"):
        load_recipe(str(path))


def test_training_exports_into_its_run_unless_shipped(tmp_path) -> None:
    trainer = trainer_for(build_config({"scene": "two_blocks", "n_envs": 1}, {"run_dir": tmp_path}))
    assert trainer.export_dir == tmp_path / "export"
    default_run = trainer_for(TrainConfig(scene="two_blocks", n_envs=1, seed=5)).run_dir
    assert default_run == PROJECT_ROOT / "runs" / "two_blocks-hierarchical" / "seed5"
    shipped, _ = train_config(["--recipe", "two_blocks", "--ship"])
    assert shipped.export_dir == checkout_models_dir() / "two_blocks" == PROJECT_ROOT / "src/semgoal_policy/models/two_blocks"


@pytest.mark.parametrize("native", [True, False])
def test_bf16_where_the_cpu_emulates_it_is_warned_of(native, monkeypatch, capsys) -> None:
    monkeypatch.setattr("semgoal_policy.sac.bf16_is_native", lambda: native)
    config, _ = train_config(["--scene", "two_blocks", "--precision", "bf16"])
    assert config.sac.precision == "bf16"
    assert ("no bfloat16 in hardware" in capsys.readouterr().err) is not native
