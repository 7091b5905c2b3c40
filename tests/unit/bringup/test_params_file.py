"""The nodes' YAML parameter file names exactly the parameters each node declares (ROS ignores a
misspelt key silently), with values of the declared types."""

import ast
import re
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[3]
PARAMS = yaml.safe_load((ROOT / "src/semgoal_bringup/config/semgoal.yaml").read_text())
NODE_SOURCES = {
    "sim": "src/semgoal_sim/semgoal_sim/sim_node.py",
    "predicates": "src/semgoal_sim/semgoal_sim/predicate_node.py",
    "planner": "src/semgoal_planner/semgoal_planner/planner_node.py",
    "policy": "src/semgoal_policy/semgoal_policy/policy_node.py",
}
DECLARATION = re.compile(r'declare_parameter\("(\w+)", ([^)]+)\)')


@pytest.mark.parametrize("node", list(NODE_SOURCES))
def test_yaml_matches_declared_parameters(node: str) -> None:
    source = (ROOT / NODE_SOURCES[node]).read_text()
    declared = {name: ast.literal_eval(default) for name, default in DECLARATION.findall(source)}
    assert set(PARAMS) <= set(NODE_SOURCES)
    values = PARAMS.get(node, {}).get("ros__parameters", {})  # a node without parameters has no section
    assert set(values) == set(declared), f"{node}: YAML {sorted(values)} vs declared {sorted(declared)}"
    for name, value in values.items():
        assert type(value) is type(declared[name]), f"{node}.{name}: {value!r} is not a {type(declared[name]).__name__}"


def test_planner_defaults_are_the_executives() -> None:
    from semgoal_planner.executive import Executive

    source = (ROOT / NODE_SOURCES["planner"]).read_text()
    declared = {name: ast.literal_eval(default) for name, default in DECLARATION.findall(source)}
    defaults = Executive.__dataclass_fields__
    assert {name: value for name, value in declared.items() if name in defaults} == {
        name: defaults[name].default for name in declared if name in defaults}
