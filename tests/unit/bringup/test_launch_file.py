"""The launch file starts what `./semgoal up` starts. ``ros2 launch`` is not installable here, so stand-in
``launch`` / ``launch_ros`` modules record its calls; the installed file is read through the ament index."""

import importlib.util
import json
import sys
import tempfile
import types
from dataclasses import dataclass, field
from pathlib import Path

import pytest
import yaml

from semgoal_bringup.graph import LAUNCH_ARGUMENTS, STATE_DIR_PREFIX, graph_nodes, params_file, rviz_config
from semgoal_ros import interfaces as topics
from semgoal_ros.package_data import share_path


@dataclass
class Recorded:
    """Any launch action: its positional and keyword arguments."""

    args: tuple = ()
    kwargs: dict = field(default_factory=dict)

    def __init__(self, *args, **kwargs) -> None:
        self.args, self.kwargs = args, kwargs


class LaunchConfiguration:
    def __init__(self, name: str) -> None:
        self.name = name

    def perform(self, context: dict) -> str:
        return context[self.name]


@pytest.fixture
def launch_file(monkeypatch):
    """The installed launch file, imported with stand-ins for launch and launch_ros."""
    modules = {name: types.ModuleType(name) for name in
               ("launch", "launch.actions", "launch.event_handlers", "launch.substitutions", "launch_ros",
                "launch_ros.actions")}
    modules["launch"].LaunchDescription = Recorded
    modules["launch.actions"].DeclareLaunchArgument = type("DeclareLaunchArgument", (Recorded,), {})
    modules["launch.actions"].OpaqueFunction = type("OpaqueFunction", (Recorded,), {})
    modules["launch.actions"].RegisterEventHandler = type("RegisterEventHandler", (Recorded,), {})
    modules["launch.event_handlers"].OnShutdown = type("OnShutdown", (Recorded,), {})
    modules["launch.substitutions"].LaunchConfiguration = LaunchConfiguration
    modules["launch_ros.actions"].Node = type("Node", (Recorded,), {})
    for name, module in modules.items():
        monkeypatch.setitem(sys.modules, name, module)
    path = share_path("semgoal_bringup", "launch", "semgoal.launch.py")
    spec = importlib.util.spec_from_file_location("semgoal_launch", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    module.handlers = []
    yield module
    for handler in module.handlers:  # the launch shuts down: its journal folders go
        handler.args[0].kwargs["on_shutdown"](None, None)


def _launched(launch_file, **given) -> list[Recorded]:
    """The nodes launched with the arguments ``given``."""
    return [action for action in _actions(launch_file, **given) if type(action).__name__ == "Node"]


def _actions(launch_file, **given) -> list[Recorded]:
    """Every action the launch takes with the arguments ``given``: its nodes and its handlers."""
    description = launch_file.generate_launch_description()
    actions = description.args[0]
    declared = {a.args[0]: a.kwargs["default_value"] for a in actions if type(a).__name__ == "DeclareLaunchArgument"}
    assert declared == {name: default for name, default, _ in LAUNCH_ARGUMENTS}
    opaque = [a for a in actions if type(a).__name__ == "OpaqueFunction"]
    taken = opaque[0].kwargs["function"]({**declared, **given})
    launch_file.handlers += [action for action in taken if type(action).__name__ == "RegisterEventHandler"]
    return taken


@pytest.mark.parametrize("given, task, seed, mode", [
    ({}, "DC-3", 0, "realtime"),
    ({"task": "MC-3", "seed": "7", "mode": "lockstep"}, "MC-3", 7, "lockstep"),
    ({"scene": "two_blocks", "task": ""}, "MC-2", 0, "realtime"),
])
def test_the_launch_file_starts_the_graph_that_up_starts(launch_file, given, task, seed, mode) -> None:
    launched = _launched(launch_file, **given)
    planner = next(n.kwargs["parameters"][1] for n in launched if n.kwargs["executable"] == "planner_node")
    assert Path(planner["state_dir"]).is_dir()  # a journal folder of its own, so a respawned planner carries on
    expected = graph_nodes(task, seed, mode, state_dir=planner["state_dir"])
    assert [(n.kwargs["package"], n.kwargs["executable"]) for n in launched] == [(p, e) for p, e, _ in expected]
    for node, (_, _, params) in zip(launched, expected, strict=True):
        assert node.kwargs["parameters"] == [str(params_file()), params]
        assert node.kwargs["respawn"] is True  # a node that dies is started again, as ./semgoal up does


def test_a_journal_folder_made_for_the_launch_goes_when_it_shuts_down_and_one_given_stays(launch_file, tmp_path) -> None:
    for given in ("", str(tmp_path)):
        *nodes, handler = _actions(launch_file, state_dir=given)
        journal = Path(next(n.kwargs["parameters"][1]["state_dir"] for n in nodes
                            if n.kwargs["executable"] == "planner_node"))
        assert type(handler).__name__ == "RegisterEventHandler" and journal.is_dir()
        assert journal == tmp_path if given else journal.name.startswith(STATE_DIR_PREFIX)
        handler.args[0].kwargs["on_shutdown"](None, None)
        assert journal.is_dir() == bool(given)


def test_rviz_and_a_recorder_join_on_request_and_a_task_of_another_scene_is_refused(launch_file, tmp_path) -> None:
    launched = _launched(launch_file, rviz="true", record=str(tmp_path / "run.mcap"))
    assert launched[-1].kwargs["executable"] == "rviz2" and launched[-1].kwargs["arguments"] == ["-d", str(rviz_config())]
    assert launched[0].kwargs["executable"] == "record_node"
    assert launched[0].kwargs["parameters"][1] == {"path": str(tmp_path / "run.mcap")}
    with pytest.raises(ValueError, match="runs in scene desk_cleanup, not two_blocks"):
        _launched(launch_file, scene="two_blocks", task="DC-3")


def test_the_live_view_and_the_console_join_on_request_with_their_ports(launch_file) -> None:
    launched = _launched(launch_file, foxglove="9001", console="9002")
    assert [(n.kwargs["executable"], n.kwargs["parameters"][1]) for n in launched[-2:]] == \
        [("foxglove_node", {"port": 9001}), ("console_node", {"port": 9002})]
    assert not {"foxglove_node", "console_node"} & {n.kwargs["executable"] for n in _launched(launch_file)}
    made_before = set(Path(tempfile.gettempdir()).glob(f"{STATE_DIR_PREFIX}*"))
    for name in ("foxglove", "console"):
        with pytest.raises(ValueError, match=f"{name} must be a port number"):
            _launched(launch_file, **{name: "eighty"})
    assert set(Path(tempfile.gettempdir()).glob(f"{STATE_DIR_PREFIX}*")) <= made_before  # no journal folder left


def test_the_foxglove_layout_shows_what_the_live_view_serves() -> None:
    from semgoal_bringup.tools.foxglove_node import SCENE_TOPIC

    layout = json.loads(share_path("semgoal_bringup", "foxglove", "semgoal.json").read_text())
    panels = layout["configById"]
    assert panels["3D!scene"]["topics"] == {SCENE_TOPIC: {"visible": True}}
    assert panels["Image!camera"]["imageMode"]["imageTopic"] == topics.CAMERA_IMAGE
    assert {p["topicPath"].split(".")[0] for k, p in panels.items() if k.startswith("RawMessages!")} == \
        {topics.PLAN, topics.SEMANTIC_STATE}
    assert {p["serviceName"] for k, p in panels.items() if k.startswith("CallService!")} == {topics.EDIT_PLAN, topics.GET_PLAN}

    def leaves(node):
        return [node] if isinstance(node, str) else leaves(node["first"]) + leaves(node["second"])
    assert sorted(leaves(layout["layout"])) == sorted(panels)  # every panel placed, none missing


def test_the_rviz_file_shows_topics_the_graph_has() -> None:
    view = yaml.safe_load(rviz_config().read_text())
    shown = {d["Topic"]["Value"] for d in view["Visualization Manager"]["Displays"] if "Topic" in d}
    assert shown == {topics.MARKERS, topics.PLAN_MARKERS, topics.CAMERA_IMAGE}
    assert view["Visualization Manager"]["Global Options"]["Fixed Frame"] == "world"


def test_composed_puts_the_graphs_nodes_in_one_process_with_their_own_values(launch_file) -> None:
    launched = _launched(launch_file, task="MC-3", seed="7", mode="lockstep", composed="true", console="8080")
    composed, *others = launched
    assert composed.kwargs["executable"] == "graph_node" and composed.kwargs["parameters"] == [str(params_file())]
    assert composed.kwargs["arguments"] == ["--nodes", "sim_node,predicate_node,planner_node,policy_node"]
    scoped = composed.kwargs["ros_arguments"]
    assert {"sim:task:=MC-3", "sim:seed:=7", "sim:mode:=lockstep", "planner:scene:=three_blocks"} <= set(scoped)
    assert [n.kwargs["executable"] for n in others] == ["console_node"]


def test_composed_with_robots_2_runs_the_second_arms_policy_node_in_the_process_under_its_namespace(launch_file):
    (composed,) = _launched(launch_file, task="DC-4", mode="lockstep", composed="true", robots="2")
    arguments = composed.kwargs["arguments"]
    assert arguments[:2] == ["--nodes", "sim_node,predicate_node,planner_node,policy_node,robot2/policy_node"]
    assert {"robot2/policy_node:arm:=2", "robot2/policy_node:arms:=2"} <= set(arguments[3::2])
    assert set(arguments[2::2]) == {"--param"}
    scoped = composed.kwargs["ros_arguments"]  # -p scopes by node name alone: /policy's values, never /robot2's
    assert "policy:arms:=2" in scoped and not any(":arm:=" in arg for arg in scoped)


def test_robots_2_adds_the_second_arms_policy_node_in_its_namespace(launch_file) -> None:
    launched = _launched(launch_file, task="DC-4", mode="lockstep", robots="2")
    by_name = {(n.kwargs["executable"], n.kwargs["namespace"]): n.kwargs["parameters"][1] for n in launched}
    assert by_name[("sim_node", None)]["arms"] == 2 and by_name[("planner_node", None)]["arms"] == 2
    assert by_name[("policy_node", None)]["arms"] == 2 and "arm" not in by_name[("policy_node", None)]
    assert by_name[("policy_node", "/robot2")] == {**by_name[("policy_node", None)], "arm": 2}
    with pytest.raises(ValueError, match="robots must be 1 to 2"):
        _launched(launch_file, robots="3")


def test_with_two_arms_from_the_camera_the_planner_hears_where_blocks_and_hands_are_from_the_camera() -> None:
    from semgoal_bringup.graph import Sight
    from semgoal_ros import interfaces as topics

    planner = {executable: params for _, executable, params in graph_nodes(
        "DC-4", 0, "lockstep", robots=2, sight=Sight("camera", "truth"))}["planner_node"]
    assert planner["world_topic"] == topics.PERCEIVED_WORLD
    for robots, sight in ((1, Sight("camera", "truth")), (2, Sight("truth", "truth"))):
        nodes = {executable: params for _, executable, params in graph_nodes("DC-4", 0, "lockstep", robots=robots,
                                                                              sight=sight)}
        assert "world_topic" not in nodes["planner_node"]


def test_the_shipped_voter_sees_every_scene_the_tabletop_too() -> None:
    from semgoal_bringup.graph import Sight
    from semgoal_core.vocabulary import BLOCK_COLOURS
    from semgoal_perception.voter_colours import exported_colours
    from semgoal_ros.package_data import share_path

    assert exported_colours(share_path("semgoal_perception", "models", "block_voter")) == tuple(BLOCK_COLOURS)
    assert graph_nodes("Clean-8", 0, "lockstep", sight=Sight("camera", "camera"))


def test_blocks_the_voter_was_not_trained_on_are_refused_with_what_to_do_instead(monkeypatch, capsys) -> None:
    """A voter of the paper's four colours (the one shipped before the tabletop's frames) cannot see orange."""
    import argparse

    from semgoal_bringup.graph import Sight, add_sight_arguments, sight_of
    from semgoal_perception import voter_colours

    monkeypatch.setattr(voter_colours, "exported_colours", lambda folder: voter_colours.colours_of(5))
    with pytest.raises(ValueError, match=r"Tower-5 from the camera: the block voter knows red, green, blue, yellow, not "
                                         r"orange: .* or see it by the simulator's poses"):
        graph_nodes("Tower-5", 0, "lockstep", sight=Sight("camera", "truth"))
    assert graph_nodes("Tower-5", 0, "lockstep")  # by the simulator's poses it runs
    assert graph_nodes("Tower-4", 0, "lockstep", sight=Sight("camera", "truth"))  # four colours it knows
    parser = argparse.ArgumentParser(prog="semgoal demo")
    add_sight_arguments(parser)
    args = parser.parse_args(["--perception", "camera"])
    assert sight_of(args, parser, ["DC-3"]).perception == "camera"
    with pytest.raises(SystemExit) as stopped:
        sight_of(args, parser, ["DC-3", "Clean-6"])
    assert stopped.value.code == 2 and "not orange, purple" in capsys.readouterr().err
