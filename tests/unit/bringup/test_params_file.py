"""The nodes' YAML parameter file names exactly the parameters each node declares (ROS ignores a
misspelt key silently), with values of the declared types that the node accepts."""

import importlib
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[3]
SECTIONS = yaml.safe_load((ROOT / "src/semgoal_bringup/config/semgoal.yaml").read_text())
PARAMS = {key.removeprefix("/**/"): section for key, section in SECTIONS.items()}
NODE_MODULES = {
    "sim": "semgoal_sim.sim_node",
    "predicates": "semgoal_sim.predicate_node",
    "planner": "semgoal_planner.planner_node",
    "policy": "semgoal_policy.policy_node",
    "foxglove": "semgoal_bringup.tools.foxglove_node",
    "console": "semgoal_bringup.tools.console",
    "perception": "semgoal_perception.perception_node",
}


def declared(node: str) -> dict:
    return {param.name: param for param in getattr(importlib.import_module(NODE_MODULES[node]), "PARAMS", ())}


@pytest.mark.parametrize("node", list(NODE_MODULES))
def test_yaml_matches_declared_parameters(node: str) -> None:
    specs = declared(node)
    assert set(PARAMS) <= set(NODE_MODULES)
    assert all(key.startswith("/**/") for key in SECTIONS)  # a node under a namespace reads its section too
    values = PARAMS.get(node, {}).get("ros__parameters", {})  # a node without parameters has no section
    assert set(values) == set(specs), f"{node}: YAML {sorted(values)} vs declared {sorted(specs)}"
    for name, value in values.items():
        assert type(value) is type(specs[name].default), f"{node}.{name}: {value!r} is not a {type(specs[name].default).__name__}"
        assert not specs[name].problem(value), f"{node}.{name}: {value!r} {specs[name].problem(value)}"
        assert specs[name].description


def test_planner_defaults_are_the_executives() -> None:
    from semgoal_planner.executive import Executive

    defaults = Executive.__dataclass_fields__
    specs = declared("planner")
    assert {name: spec.default for name, spec in specs.items() if name in defaults} == {
        name: defaults[name].default for name in specs if name in defaults}
