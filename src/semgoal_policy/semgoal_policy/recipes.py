"""Training recipes as data: ``recipes/<scene>[-<agent>].yaml`` holds every setting of a shipped actor's run
but the run's own (seed, directories, command line), so ``./semgoal train --recipe desk_cleanup --seed 81``
trains with exactly the shipped configuration.

The ``train`` command's flags are generated from :class:`~semgoal_policy.trainer.TrainConfig` and
:class:`~semgoal_policy.sac.SacConfig`, their help from the fields' docstrings: a new setting is a new
field, nothing else. A flag given on the command line wins over the recipe, the recipe over the defaults.
"""

from __future__ import annotations

import argparse
import ast
import dataclasses
import inspect
import itertools
import math
import textwrap
import typing
from pathlib import Path

import yaml

from semgoal_policy.sac import SacConfig
from semgoal_policy.trainer import Phase, TrainConfig
from semgoal_ros.package_data import share_path

RUN_FIELDS = ("seed", "run_dir", "export_dir", "command", "tensorboard")
"""A run's own settings (who it is, where it writes): never part of a recipe."""
FLAG_NAMES = {"n_envs": "--envs", "derived_features": "--derive"}
"""Flags whose names are shorter than their fields'."""


class RecipeError(ValueError):
    """A recipe that does not exist or names settings the configuration does not have."""


def recipes_dir() -> Path:
    """The recipes as installed: ``share/semgoal_policy/recipes``."""
    return share_path("semgoal_policy", "recipes")


def recipe_names() -> list[str]:
    return sorted(path.stem for path in recipes_dir().glob("*.yaml"))


def recipe_path(name: str) -> Path:
    """A recipe's file: a name under :func:`recipes_dir` (``desk_cleanup``, ``two_blocks-flat-semantic``) or a path."""
    path = Path(name) if name.endswith((".yaml", ".yml")) else recipes_dir() / f"{name}.yaml"
    if not path.is_file():
        raise RecipeError(f"no recipe {name!r}: recipes are {', '.join(recipe_names())} (or a path to a .yaml)")
    return path


def load_recipe(name: str) -> dict:
    """The settings a recipe holds, checked against the configuration's fields; its ``phases`` (settings that
    change during the run, each ``from_steps`` on) as :class:`Phase` values, in order."""
    values = yaml.safe_load(recipe_path(name).read_text()) or {}
    _check_fields(values, TrainConfig, name)
    _check_fields(values.get("sac", {}), SacConfig, f"{name}: sac")
    try:
        phases = tuple(Phase.from_recipe(entry) for entry in values.get("phases", ()))
    except (ValueError, TypeError) as error:
        raise RecipeError(f"recipe {name}: {error}") from None
    starts = [phase.from_steps for phase in phases]
    if starts != sorted(set(starts)):
        raise RecipeError(f"recipe {name}: phases must start at increasing env steps, got {starts}")
    if phases:
        values["phases"] = phases
    return values


def build_config(recipe: dict, overrides: dict) -> TrainConfig:
    """A configuration from the defaults, then ``recipe``, then ``overrides`` (flags; ``sac.*`` under ``sac``)."""
    values = {**recipe, **{k: v for k, v in overrides.items() if k != "sac"}}
    sac = SacConfig(**{**recipe.get("sac", {}), **overrides.get("sac", {})})
    values["derived_features"] = tuple(values.get("derived_features", ()))
    for name in ("run_dir", "export_dir"):
        if values.get(name) is not None:
            values[name] = Path(values[name])
    _check_ranges({**values, **{f"sac.{k}": v for k, v in dataclasses.asdict(sac).items()}})
    return TrainConfig(**{**values, "sac": sac})


RANGES: dict[str, tuple[float, float, str]] = {
    "steps": (1, math.inf, "[]"), "seed": (0, math.inf, "[]"), "n_envs": (1, math.inf, "[]"),
    "updates_per_step": (0, math.inf, "(]"), "learning_starts": (0, math.inf, "[]"), "refill_steps": (0, math.inf, "[]"),
    "demo_fraction": (0, 1, "[]"), "demo_noise": (0, math.inf, "[]"), "spawn_margin": (0, math.inf, "[]"),
    "missed_put_share": (0, 1, "[]"), "max_blocks": (1, math.inf, "[]"), "tower_share": (0, 1, "[]"),
    "eval_every": (1, math.inf, "[]"), "eval_episodes": (1, math.inf, "[]"), "final_eval_episodes": (0, math.inf, "[]"),
    "max_wall_s": (0, math.inf, "(]"), "torch_threads": (1, math.inf, "[]"),
    "sac.gamma": (0, 1, "(]"), "sac.tau": (0, 1, "(]"), "sac.lr": (0, math.inf, "(]"), "sac.batch_size": (1, math.inf, "[]"),
    "sac.bc_weight": (0, math.inf, "[]"), "sac.actor_average_rate": (0, 1, "[)"), "sac.mean_reg": (0, math.inf, "[]"),
}
"""Each number's allowed range (low, high, which ends are in): a setting out of it is refused before training."""


def _check_ranges(values: dict) -> None:
    for name, (low, high, ends) in RANGES.items():
        value = values.get(name)
        if value is None:
            continue
        inside = (value >= low if ends[0] == "[" else value > low) and (value <= high if ends[1] == "]" else value < high)
        if not (math.isfinite(value) and inside):
            bound = f"{ends[0]}{low:g}, " + ("∞)" if high == math.inf else f"{high:g}{ends[1]}")
            raise RecipeError(f"setting {name} = {value!r} is out of its range {bound}")


def add_config_flags(parser: argparse.ArgumentParser) -> None:
    """One flag per setting of TrainConfig and SacConfig (``sac`` settings flat: ``--lr``), all defaulting to
    "not given", so that only what the command line says overrides the recipe."""
    for cls, group in ((TrainConfig, parser.add_argument_group("run")), (SacConfig, parser.add_argument_group("SAC"))):
        docs, hints = field_docs(cls), typing.get_type_hints(cls)
        for field in dataclasses.fields(cls):
            if field.name in ("sac", "command", "phases"):  # phases: in recipes only
                continue
            flag = FLAG_NAMES.get(field.name, "--" + field.name.replace("_", "-"))
            help_text = docs.get(field.name, "").split(". ")[0].replace("%", "%%")
            kind, metavar = hints[field.name], flag.removeprefix("--").upper().replace("-", "_")
            if kind is bool:
                group.add_argument(flag, dest=field.name, action=argparse.BooleanOptionalAction,
                                   default=argparse.SUPPRESS, help=help_text)
            elif typing.get_origin(kind) is tuple:
                group.add_argument(flag, dest=field.name, action="append", default=argparse.SUPPRESS,
                                   metavar=metavar, help=help_text + " (repeatable)")
            else:
                convert = next(t for t in typing.get_args(kind) or (kind,) if t is not type(None))
                group.add_argument(flag, dest=field.name, type=convert, default=argparse.SUPPRESS,
                                   metavar=metavar, help=help_text)


def flag_overrides(args: argparse.Namespace) -> dict:
    """The settings given on the command line, ``sac`` ones under ``sac``."""
    given = vars(args)
    sac_names = {f.name for f in dataclasses.fields(SacConfig)}
    train_names = {f.name for f in dataclasses.fields(TrainConfig)} - {"sac", "phases"}
    overrides = {name: value for name, value in given.items() if name in train_names}
    overrides["sac"] = {name: value for name, value in given.items() if name in sac_names}
    return overrides


def field_docs(cls: type) -> dict[str, str]:
    """The docstrings under a dataclass's fields (the string right after each annotated assignment)."""
    body = ast.parse(textwrap.dedent(inspect.getsource(cls))).body[0].body
    docs = {}
    for node, after in itertools.pairwise(body):
        if (isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name) and isinstance(after, ast.Expr)
                and isinstance(after.value, ast.Constant) and isinstance(after.value.value, str)):
            docs[node.target.id] = " ".join(after.value.value.split())
    return docs


def _check_fields(values: dict, cls: type, where: str) -> None:
    known = {f.name for f in dataclasses.fields(cls)} - set(RUN_FIELDS)
    unknown = sorted(set(values) - known)
    if unknown:
        raise RecipeError(f"recipe {where} has unknown settings {', '.join(unknown)}; valid: {', '.join(sorted(known))}")
