"""Parameters the ROS way on the real nodes: described, a bad start-up value refused with the reason (exit 2),
a change at run time applied (the planner's require_approval takes effect on the next goal) or refused."""

import subprocess

from rcl_interfaces.msg import Parameter, ParameterType, ParameterValue
from rcl_interfaces.srv import DescribeParameters, SetParameters

from conftest import GraphProbe, NodeProcesses, semantic_state
from semgoal_bringup.graph import node_command
from semgoal_msgs.msg import GoalRequest, Plan, SemanticState
from semgoal_ros import interfaces as topics


def _call(probe: GraphProbe, service_type, name: str, request):
    """The answer to ``request``, sent again while none comes (Fast DDS drops an answer to a client whose reply reader
    the server has not matched yet: ``topics.send_until_answered``); describing and setting a value are safe to
    repeat."""
    client = probe.node.create_client(service_type, name)
    probe.spin_until(client.service_is_ready, 30, name)
    answer = topics.send_until_answered(lambda: client.call_async(request), probe.poll)
    assert answer is not None, f"no answer from {name} after {topics.SEND_ATTEMPTS} tries"
    return answer


def _set(probe: GraphProbe, node: str, name: str, value: ParameterValue):
    request = SetParameters.Request(parameters=[Parameter(name=name, value=value)])
    return _call(probe, SetParameters, f"/{node}/set_parameters", request).results[0]


def test_a_bad_start_up_value_stops_the_node_with_the_reason(ros_domain) -> None:
    for package, executable, params, said in (
            ("semgoal_sim", "sim_node", {"rate_hz": -1.0}, "parameter rate_hz"),
            ("semgoal_sim", "sim_node", {"mode": "fast"}, "mode='fast' must be one of lockstep, realtime"),
            ("semgoal_planner", "planner_node", {"scene": "kitchen"}, "scene='kitchen' must be one of"),
            ("semgoal_policy", "policy_node", {"model_dir": "/nowhere"}, "policy: ")):
        run = subprocess.run(node_command(package, executable, params), capture_output=True, text=True, timeout=120)
        assert run.returncode == 2 and said in run.stderr, (executable, run.returncode, run.stderr[-2000:])
        assert "Traceback" not in run.stderr


def test_planner_parameters_are_described_applied_and_refused(nodes: NodeProcesses, probe: GraphProbe) -> None:
    nodes.start("semgoal_planner", "planner_node", params={"scene": "desk_cleanup"})
    described = _call(probe, DescribeParameters, "/planner/describe_parameters",
                      DescribeParameters.Request(names=["scene", "stall_steps", "require_approval"])).descriptors
    assert described[0].read_only and "desk_cleanup" in described[0].additional_constraints
    assert not described[1].read_only and described[1].integer_range[0].from_value == 1
    assert described[2].description

    refused = _set(probe, "planner", "scene", ParameterValue(type=ParameterType.PARAMETER_STRING, string_value="two_blocks"))
    assert not refused.successful and "read-only" in refused.reason
    refused = _set(probe, "planner", "stall_steps", ParameterValue(type=ParameterType.PARAMETER_INTEGER, integer_value=0))
    assert not refused.successful
    applied = _set(probe, "planner", "require_approval", ParameterValue(type=ParameterType.PARAMETER_BOOL, bool_value=True))
    assert applied.successful

    plans: list[Plan] = []
    probe.node.create_subscription(Plan, topics.PLAN, plans.append, topics.LATCHED)
    states = probe.node.create_publisher(SemanticState, topics.SEMANTIC_STATE, topics.PER_STEP)
    goals = probe.node.create_publisher(GoalRequest, topics.GOAL, 10)
    probe.spin_until(lambda: goals.get_subscription_count() > 0 and states.get_subscription_count() > 0, 30, "planner")
    states.publish(semantic_state(set(), 0))
    probe.spin_for(0.5)
    goals.publish(GoalRequest(task="DC-3"))
    probe.spin_until(lambda: plans and plans[-1].status == Plan.STATUS_AWAITING_APPROVAL, 30,
                     "the plan to wait for approval, as require_approval now says")
