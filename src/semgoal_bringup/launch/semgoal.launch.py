"""The four semgoal nodes, natively: ``ros2 launch semgoal_bringup semgoal.launch.py task:=DC-3 seed:=6``.

Arguments: ``scene``, ``task``, ``seed``, ``mode`` (realtime | lockstep), ``models``, ``rviz`` (true | false),
``record`` (an MCAP file), ``foxglove`` and ``console`` (ports for the live view and the console), ``state_dir``
(the planner's journal: a respawned planner carries on with the plan), ``perception`` and ``policy_input``
(truth | camera: what the planner and the policy see by), ``composed`` (true: the graph's nodes in one process,
``graph_node``), ``robots`` (2: a second Fetch across the table, its policy node in /robot2);
``--show-args`` lists them. The nodes and their parameters come from ``semgoal_bringup.graph``, the
definition `./semgoal up` starts from, over the installed parameter file; a node that dies is started
again, as under `./semgoal up`.
"""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, OpaqueFunction, RegisterEventHandler
from launch.event_handlers import OnShutdown
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from semgoal_bringup.graph import (
    LAUNCH_ARGUMENTS,
    NAMESPACE_KEY,
    Sight,
    composed_arguments,
    composed_nodes,
    composed_parameters,
    graph_nodes,
    params_file,
    run_state_dir,
    rviz_config,
    scene_task,
)


def without_namespace(params: dict) -> dict:
    return {key: value for key, value in params.items() if key != NAMESPACE_KEY}


def generate_launch_description() -> LaunchDescription:
    arguments = [DeclareLaunchArgument(name, default_value=default, description=text)
                 for name, default, text in LAUNCH_ARGUMENTS]
    return LaunchDescription([*arguments, OpaqueFunction(function=launch_nodes)])


def launch_nodes(context) -> list[Node]:
    """The nodes for the arguments given (a task of another scene than ``scene`` stops the launch with why)."""
    value = {name: LaunchConfiguration(name).perform(context) for name, _, _ in LAUNCH_ARGUMENTS}
    task = scene_task(value["scene"], value["task"])
    state_dir, remove_state_dir = run_state_dir(value["state_dir"])  # one made for this launch goes at its shutdown
    try:
        graph = graph_nodes(task.name, int(value["seed"]), value["mode"], value["models"], value["record"],
                            value["foxglove"], value["console"], state_dir, Sight(value["perception"], value["policy_input"]),
                            int(value["robots"]))
    except ValueError:
        remove_state_dir()
        raise
    together = composed_nodes(graph, value["composed"].lower() in ("true", "1", "yes"))
    nodes = [Node(package="semgoal_bringup", executable="graph_node", output="screen", respawn=True, respawn_delay=2.0,
                  arguments=composed_arguments(together), ros_arguments=composed_parameters(together),
                  parameters=[str(params_file())])] if together else []
    nodes += [Node(package=package, executable=executable, output="screen", respawn=True, respawn_delay=2.0,
                   namespace=params.get(NAMESPACE_KEY), parameters=[str(params_file()), without_namespace(params)])
              for package, executable, params in graph if (package, executable, params) not in together]
    if value["rviz"].lower() in ("true", "1", "yes"):
        nodes.append(Node(package="rviz2", executable="rviz2", output="screen", arguments=["-d", str(rviz_config())]))
    return [*nodes, RegisterEventHandler(OnShutdown(on_shutdown=lambda event, context: remove_state_dir()))]
