"""The four nodes as separate processes: the one definition of what `./semgoal up`, the demo, the evaluation
and the graph tests start, and what ``launch/semgoal.launch.py`` starts natively (``ros2 launch`` is not on
PyPI: here every node goes through `./semgoal run`)."""

from __future__ import annotations

import functools
import os
import subprocess
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from semgoal_bringup.composed import NODE_NAMES
from semgoal_core.tasks import get_task
from semgoal_ros.domains import domain_for_this_process

NODES = (("semgoal_sim", "sim_node"), ("semgoal_sim", "predicate_node"),
         ("semgoal_planner", "planner_node"), ("semgoal_policy", "policy_node"))
NAMESPACE_KEY = "__ns"
"""A node's namespace among its parameters in :func:`graph_nodes` (the second arm's policy node's): a remapping
when the node starts, never a parameter."""
SOURCES = ("truth", "camera")
"""Where the blocks' poses come from: the simulator's (``truth``) or the RGB-D camera's perception."""


@dataclass(frozen=True)
class Sight:
    """What the planner and the policy see by: ``perception`` camera runs perception_node in place of
    predicate_node (the sim publishes its camera); ``policy_input`` camera gives the policy the perceived
    world state (needs the camera perception); ``camera_condition``: the sim camera's look."""

    perception: str = "truth"
    policy_input: str = "truth"
    camera_condition: str = "nominal"

    def __post_init__(self) -> None:
        for name in ("perception", "policy_input"):
            if getattr(self, name) not in SOURCES:
                raise ValueError(f"{name} must be one of {', '.join(SOURCES)}, got {getattr(self, name)!r}")
        if self.policy_input == "camera" and self.perception != "camera":
            raise ValueError("the policy can only take the camera's poses when the perception runs on the camera "
                             "(perception camera)")

    def nodes(self) -> tuple[tuple[str, str], ...]:
        semantics = ("semgoal_perception", "perception_node") if self.perception == "camera" else NODES[1]
        return (NODES[0], semantics, *NODES[2:])


TRUTH = Sight()
"""The simulator's poses for everyone (the benchmark's setting)."""


def add_sight_arguments(parser) -> None:
    """``--perception``, ``--policy-input`` and ``--camera-condition`` on a command that starts the graph."""
    from semgoal_sim.camera import CONDITIONS

    parser.add_argument("--perception", default="truth", choices=SOURCES,
                        help="the planner's predicates from the simulator's poses (truth) or the RGB-D camera")
    parser.add_argument("--policy-input", default="truth", choices=SOURCES,
                        help="the policy's block poses from the simulator (truth) or the camera's perception")
    parser.add_argument("--camera-condition", default="nominal", choices=tuple(CONDITIONS),
                        help="with --perception camera: the camera's look (moved: beyond training's range)")


def sight_of(args, parser, tasks: Sequence[str] = ()) -> Sight:
    """The :class:`Sight` the arguments ask for; a parser error when they do not go together, or it cannot see one of
    ``tasks`` (:func:`check_sight`)."""
    try:
        sight = Sight(args.perception, args.policy_input, args.camera_condition)
        for task in tasks:
            check_sight(task, sight)
    except ValueError as error:
        parser.error(str(error))
    return sight


LAUNCH_ARGUMENTS = (
    ("scene", "", "two_blocks | three_blocks | desk_cleanup (empty: the task's)"),
    ("task", "DC-3", "the task whose start the sim loads (empty: the scene's first)"),
    ("seed", "0", "the task's start seed"),
    ("mode", "realtime", "realtime: the sim steps on its clock | lockstep: one step per command"),
    ("models", "", "a folder of exported actors (SCENE/actor.pt); empty: the shipped ones"),
    ("rviz", "false", "also start RViz with share/semgoal_bringup/rviz/semgoal.rviz"),
    ("record", "", "an MCAP file to record every topic into until the graph stops (empty: no recording)"),
    ("foxglove", "", "a port to serve the Foxglove live view on, at 127.0.0.1 (empty: none)"),
    ("console", "", "a port to serve the collaboration console on, at 127.0.0.1 (empty: none)"),
    ("state_dir", "", "a folder for the planner's journal, so that a restarted planner carries on with the plan "
     "(empty: a new temporary folder for this run)"),
    ("perception", "truth", "truth: predicates on the simulator's poses | camera: perception_node on the RGB-D camera"),
    ("policy_input", "truth", "truth: the policy reads the simulator's poses | camera: the perceived ones"),
    ("composed", "false", "true: the sim, predicates (or perception), planner and policy nodes in one process on one "
     "executor (graph_node) | false: a process each"),
    ("robots", "1", "robot arms at the table: 2 adds a second Fetch across it, driven by a second policy node in "
     "/robot2 (its topics under /semgoal/robot2/)"),
)
"""The launch file's arguments (name, default, description); `./semgoal up` takes the same as options."""


def scene_task(scene: str, task_name: str):
    """The task to start: ``task_name`` (in ``scene`` when one is given), else ``scene``'s first; ValueError if
    the two disagree."""
    from semgoal_core.tasks import ALL_TASKS

    if not task_name:
        if not scene:
            raise ValueError("give a task or a scene")
        first = next((t for t in ALL_TASKS.values() if t.scene == scene), None)
        if first is None:
            raise ValueError(f"unknown scene {scene!r}")
        return first
    task = get_task(task_name)
    if scene and task.scene != scene:
        raise ValueError(f"task {task.name} runs in scene {task.scene}, not {scene}")
    return task


def check_sight(task_name: str, sight: Sight) -> None:
    """ValueError, with what to do instead, where ``sight``'s camera cannot see ``task_name``'s blocks: the shipped
    block voter was not trained on their colours."""
    from semgoal_perception.voter_colours import check_blocks, exported_colours
    from semgoal_ros.package_data import share_path

    if sight.perception != "camera":
        return
    try:
        check_blocks(exported_colours(share_path("semgoal_perception", "models", "block_voter")), get_task(task_name).blocks)
    except ValueError as error:
        raise ValueError(f"{task_name} from the camera: {error}; or see it by the simulator's poses (perception truth)"
                         ) from None


def graph_nodes(task_name: str, seed: int, mode: str, models: str = "", record: str = "",
                foxglove: str = "", console: str = "", state_dir: str = "",
                sight: Sight = TRUTH, robots: int = 1) -> list[tuple[str, str, dict[str, object]]]:
    """(package, executable, parameters on top of :func:`params_file`) of every node, in start order; with
    ``record``, a recorder first, so that it hears the graph from its first message; with ``foxglove`` or
    ``console`` (a port each), the live view and the console last; with ``robots`` 2, a second policy node (its
    namespace under :data:`NAMESPACE_KEY`). ValueError for a port that is not a number, two arms that cannot be, or
    a camera that cannot see the task's scene."""
    from semgoal_core.arms import MAX_ARMS, arm_namespace

    if not 1 <= robots <= MAX_ARMS:
        raise ValueError(f"robots must be 1 to {MAX_ARMS}")
    check_sight(task_name, sight)
    params = node_params(task_name, seed, mode, models, state_dir, sight, robots)
    recorder = [("semgoal_bringup", "record_node", {"path": str(Path(record).resolve())})] if record else []
    views = []
    for name, port, executable in (("foxglove", foxglove, "foxglove_node"), ("console", console, "console_node")):
        if port and not port.isdigit():
            raise ValueError(f"{name} must be a port number, got {port!r}")
        views += [("semgoal_bringup", executable, {"port": int(port)})] if port else []
    arms = [("semgoal_policy", "policy_node", {**params["policy_node"], "arm": arm + 1, NAMESPACE_KEY: f"/{arm_namespace(arm)}"})
            for arm in range(1, robots)]
    return [*recorder, *((package, executable, params[executable]) for package, executable in sight.nodes()), *arms,
            *views]


STATE_DIR_PREFIX = "semgoal-planner-"
"""The temporary journal folders' names begin so (in the system's temporary folder)."""


def run_state_dir(given: str) -> tuple[str, Callable[[], None]]:
    """The planner's journal folder for a graph that restarts dead nodes, and what to call when the graph stops:
    ``given``, kept; else a new temporary one, then removed (a journal of an earlier run is never taken up by a new
    graph)."""
    import shutil
    import tempfile

    if given:
        return given, lambda: None
    made = tempfile.mkdtemp(prefix=STATE_DIR_PREFIX)
    return made, functools.partial(shutil.rmtree, made, ignore_errors=True)


def rviz_config() -> Path:
    """The RViz view of the graph as installed: share/semgoal_bringup/rviz/semgoal.rviz."""
    from semgoal_ros.package_data import share_path

    return share_path("semgoal_bringup", "rviz", "semgoal.rviz")


def node_params(task_name: str, seed: int, mode: str, models: str = "",
                state_dir: str = "", sight: Sight = TRUTH, robots: int = 1) -> dict[str, dict[str, object]]:
    """The task's own parameters per executable, set on top of :func:`params_file`; ``state_dir``: the planner's
    journal (empty: none); ``robots``: the arms at the table (set only when there are two)."""
    from semgoal_ros import interfaces as topics

    task = get_task(task_name)
    camera = {"camera": True, "camera_condition": sight.camera_condition} if sight.perception == "camera" else {}
    world = {"world_topic": topics.PERCEIVED_WORLD} if sight.policy_input == "camera" else {}
    two = robots > 1
    return {
        "sim_node": {"scene": task.scene, "task": task.name, "seed": seed, "mode": mode, **camera,
                     **({"arms": robots} if two else {})},
        "predicate_node": {},
        "perception_node": {"arms": robots} if two else {},
        "planner_node": {"scene": task.scene, **({"state_dir": state_dir} if state_dir else {}),
                         **({"arms": robots} if two else {}),
                         **({"world_topic": topics.PERCEIVED_WORLD} if two and sight.perception == "camera" else {})},
        "policy_node": {"scene": task.scene, "mode": mode, **({"model_dir": model_dir} if (model_dir := policy_model_dir(
                            task.scene, models)) else {}),
                        **world, **({"arms": robots} if two else {})},
    }


def policy_model_dir(scene: str, models: str = "") -> str:
    """The policy node's ``model_dir``: ``expert`` for ``models`` ``expert`` or for a scene with no shipped actor (the
    scripted expert, the actors' teacher, drives the arm), else the scene's
    folder under ``models``, else "" (the shipped actor)."""
    from semgoal_policy import actor as actor_io
    from semgoal_policy.expert_actor import EXPERT

    if models == EXPERT or not (models or (actor_io.models_dir() / scene / "actor.json").exists()):
        return EXPERT
    return f"{models}/{scene}" if models else ""


def params_file() -> Path:
    """The nodes' parameter file as installed: share/semgoal_bringup/config/semgoal.yaml."""
    from semgoal_ros.package_data import share_path

    return share_path("semgoal_bringup", "config", "semgoal.yaml")


def node_command(package: str, executable: str, params: dict | None = None, log_level: str | None = None) -> list[str]:
    """`./semgoal run PKG EXE --ros-args --params-file semgoal.yaml -p key:=value ...`: the file's values,
    then ``params`` on top, as a launch file passes a YAML and per-launch overrides."""
    args = [str(Path(os.environ["SEMGOAL_ROOT"]) / "semgoal"), "run", package, executable,
            "--ros-args", "--params-file", str(params_file())]
    if log_level:
        args += ["--log-level", log_level]
    for key, value in (params or {}).items():
        args += ["-r", f"__ns:={value}"] if key == NAMESPACE_KEY else ["-p", f"{key}:={value}"]
    return args


def start_graph(task_name: str, seed: int, mode: str = "lockstep", log_level: str = "warn",
                skip: tuple[str, ...] = (), models: str = "", record: str = "",
                foxglove: str = "", console: str = "", sight: Sight = TRUTH,
                composed: bool = False, robots: int = 1) -> dict[str, subprocess.Popen]:
    """Start the nodes (all but ``skip``); ``models``: a folder of exported actors instead of the shipped ones;
    ``record``: an MCAP file that a recorder node writes everything into; ``foxglove``, ``console``: ports for the
    live view and the console; ``sight``: what the planner and the policy see by; ``composed``: the graph's own
    nodes in one process (:mod:`semgoal_bringup.composed`), the others apart; ``robots``: the arms at the table."""
    nodes = [node for node in graph_nodes(task_name, seed, mode, models, record, foxglove, console, sight=sight,
                                          robots=robots) if node[1] not in skip]
    return {name: subprocess.Popen(command) for name, command in graph_commands(nodes, composed, log_level).items()}


def graph_commands(nodes: list[tuple[str, str, dict]], composed: bool = False, log_level: str | None = None
                   ) -> dict[str, list[str]]:
    """The command of each process that runs ``nodes`` (:func:`graph_nodes`), by its name: a process per node, or
    (``composed``) the graph's own nodes in one, ``graph_node``, and the others a process each."""
    together = composed_nodes(nodes, composed)
    commands = {process_name(executable, params): node_command(package, executable, params, log_level)
                for package, executable, params in nodes if (package, executable, params) not in together}
    return {**({"graph_node": composed_command(together, log_level)} if together else {}), **commands}


def composed_nodes(nodes: list[tuple[str, str, dict]], composed: bool) -> list[tuple[str, str, dict]]:
    """The nodes ``graph_node`` runs when ``composed``: the graph's own (the second arm's policy node too, in /robot2)."""
    return [node for node in nodes if composed and node[1] in NODE_NAMES]


def process_name(executable: str, params: dict) -> str:
    """A node's process name: its executable, under its namespace if it has one (``robot2/policy_node``)."""
    namespace = str(params.get(NAMESPACE_KEY, "")).strip("/")
    return f"{namespace}/{executable}" if namespace else executable


def composed_command(nodes: list[tuple[str, str, dict]], log_level: str | None = None) -> list[str]:
    """`./semgoal run semgoal_bringup graph_node --nodes ... --ros-args --params-file semgoal.yaml -p node:key:=value`:
    the params file, and over it each node's own values, scoped to its name (a plain ``-p`` would set every node's)."""
    command = [str(Path(os.environ["SEMGOAL_ROOT"]) / "semgoal"), "run", "semgoal_bringup", "graph_node",
               *composed_arguments(nodes), "--ros-args", "--params-file", str(params_file())]
    return command + (["--log-level", log_level] if log_level else []) + composed_parameters(nodes)


def composed_arguments(nodes: list[tuple[str, str, dict]]) -> list[str]:
    """``graph_node``'s own arguments: which nodes it runs (``robot2/policy_node`` under its namespace), and the
    values of those under a namespace (``--param robot2/policy_node:arm:=2``: ROS's ``-p`` cannot tell them apart)."""
    entries = [(process_name(executable, params), params) for _, executable, params in nodes]
    return ["--nodes", ",".join(entry for entry, _ in entries),
            *(arg for entry, params in entries if NAMESPACE_KEY in params for key, value in params.items()
              if key != NAMESPACE_KEY for arg in ("--param", f"{entry}:{key}:={value}"))]


def composed_parameters(nodes: list[tuple[str, str, dict]]) -> list[str]:
    """The values of each node in the root namespace as ROS arguments scoped to its name, ``-p sim:task:=DC-3``."""
    return [arg for _, executable, params in nodes if NAMESPACE_KEY not in params for key, value in params.items()
            for arg in ("-p", f"{NODE_NAMES[executable]}:{key}:={value}")]


def stop_graph(processes: dict[str, subprocess.Popen]) -> None:
    for process in processes.values():
        process.terminate()
    for process in processes.values():
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()


@contextmanager
def running_graph(task_name: str, seed: int, mode: str = "lockstep", client_name: str = "semgoal_operator",
                  models: str = "", watch: bool = True, sight: Sight = TRUTH, composed: bool = False,
                  robots: int = 1) -> Iterator:
    """The four nodes (with ``robots`` 2, the second arm's policy node too) and a :class:`GraphClient` on a ROS domain
    of their own (:mod:`semgoal_ros.domains`), ready; all stopped on exit. ``watch``: the client subscribes to the
    per-step streams. RuntimeError when the nodes do not come up."""
    from semgoal_ros.client import GraphClient

    with domain_for_this_process():
        processes = start_graph(task_name, seed, mode=mode, models=models, sight=sight, composed=composed,
                                robots=robots)
        client = None
        try:
            client = GraphClient(client_name, watch=watch, lockstep=mode == "lockstep")
            if not client.wait_ready(arms=robots):
                raise RuntimeError(f"the node graph for {task_name} did not come up")
            yield client
        finally:
            if client is not None:
                client.close()
            stop_graph(processes)
