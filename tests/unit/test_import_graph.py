"""The packages' import graph: core <- ros <- {sim, planner, policy, perception} <- bringup (the middle
four never import each other), the general planner (strips_planner) imports nothing of semgoal, and the
nodes that only read world states (predicates, planner, policy) and the whole perception package (it sees
through the camera, never the simulator) load no MuJoCo."""

import ast
import subprocess
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).parents[2] / "src"
ALLOWED = {
    "strips_planner": set(),
    "semgoal_core": set(),
    "semgoal_ros": {"semgoal_core", "semgoal_msgs"},
    "semgoal_sim": {"semgoal_core", "semgoal_ros", "semgoal_msgs"},
    "semgoal_planner": {"semgoal_core", "semgoal_ros", "semgoal_msgs"},
    "semgoal_policy": {"semgoal_core", "semgoal_ros", "semgoal_msgs"},
    "semgoal_perception": {"semgoal_core", "semgoal_ros", "semgoal_msgs"},
}


def semgoal_imports(path: Path) -> set[str]:
    """The semgoal packages a module imports (at any depth of the module: lazy imports count)."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
            [node.module or ""] if isinstance(node, ast.ImportFrom) else []
        found |= {name.split(".")[0] for name in names if name.startswith("semgoal_")}
    return found


@pytest.mark.parametrize("package", sorted(ALLOWED))
def test_a_package_imports_only_the_layers_below_it(package: str) -> None:
    for path in sorted((SRC / package / package).rglob("*.py")):
        assert semgoal_imports(path) - {package} <= ALLOWED[package], path.name


@pytest.mark.slow
@pytest.mark.parametrize("module", ["semgoal_sim.predicate_node", "semgoal_planner.planner_node", "semgoal_policy.policy_node",
                                    "semgoal_perception.perception_node", "semgoal_perception.training"])
def test_a_node_that_reads_world_states_loads_no_mujoco(module: str) -> None:
    loaded = subprocess.run([sys.executable, "-c", f"import sys, {module}; print('mujoco' in sys.modules)"],
                            capture_output=True, text=True, check=True).stdout.strip()
    assert loaded == "False"
