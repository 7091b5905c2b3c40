"""Names defined once (the messages' constants equal the core's), and node parameters declared the ROS way."""

import math

import pytest
import rclpy
from rclpy.parameter import Parameter

from semgoal_core.names import Assignee, Mode, PlanStatus, StepStatus
from semgoal_msgs.msg import Plan, SubGoal
from semgoal_ros.parameters import Param, ParameterValueError, apply_changes, declare


def _constants(message: type, prefix: str) -> set[str]:
    return {getattr(message, name) for name in dir(message) if name.startswith(prefix) and name.isupper()}


def test_message_constants_are_the_core_names() -> None:
    assert _constants(Plan, "STATUS_") == set(PlanStatus)
    assert _constants(SubGoal, "STATUS_") == set(StepStatus)
    assert _constants(SubGoal, "ASSIGNEE_") == set(Assignee)
    assert set(Mode) == {"lockstep", "realtime"}


PARAMS = (
    Param("mode", "lockstep", "how it steps", choices=("lockstep", "realtime")),
    Param("rate_hz", 25.0, "control rate", low=0.1, high=1000.0, runtime=True),
    Param("every", 5, "period", low=1, high=100, runtime=True),
    Param("kind", "a", "a or b", choices=("a", "b"), runtime=True),
)


@pytest.fixture
def node(ros_domain):
    rclpy.init(domain_id=ros_domain)
    made = []

    def make(overrides=()):
        made.append(rclpy.create_node("probe", parameter_overrides=[Parameter(k, value=v) for k, v in overrides]))
        return made[-1]

    yield make
    for n in made:
        n.destroy_node()
    rclpy.shutdown()


@pytest.mark.slow
def test_parameters_carry_descriptors_and_refuse_bad_start_values(node) -> None:
    probe = node()
    assert declare(probe, PARAMS) == {"mode": "lockstep", "rate_hz": 25.0, "every": 5, "kind": "a"}
    rate = probe.describe_parameter("rate_hz")
    assert rate.description == "control rate" and not rate.read_only
    assert (rate.floating_point_range[0].from_value, rate.floating_point_range[0].to_value) == (0.1, 1000.0)
    mode = probe.describe_parameter("mode")
    assert mode.read_only and "lockstep, realtime" in mode.additional_constraints
    for overrides, said in (([("mode", "fast")], "mode='fast' must be one of lockstep, realtime"),
                            ([("rate_hz", -1.0)], "rate_hz out of range .* must be within [0.1, 1000.0]"),
                            ([("rate_hz", math.nan)], "value: nan.* must be within [0.1, 1000.0]")):
        with pytest.raises(ParameterValueError, match=said.replace("[", r"\[").replace("]", r"\]").replace("(", r"\(")):
            declare(node(overrides), PARAMS)


@pytest.mark.slow
def test_changes_at_run_time_are_applied_or_refused_with_the_reason(node) -> None:
    probe = node()
    declare(probe, PARAMS)
    applied = []
    apply_changes(probe, PARAMS, lambda name, value: applied.append((name, value)))
    assert probe.set_parameters([Parameter("rate_hz", value=50.0)])[0].successful
    assert applied == [("rate_hz", 50.0)]
    refused = [probe.set_parameters([Parameter(name, value=value)])[0] for name, value in
               (("mode", "realtime"), ("rate_hz", 5000.0), ("kind", "c"), ("every", 0))]
    assert not any(result.successful for result in refused)
    assert "read-only" in refused[0].reason and "kind must be one of a, b" in refused[2].reason
    assert applied == [("rate_hz", 50.0)] and probe.get_parameter("rate_hz").value == 50.0
    assert probe.get_parameter("mode").value == "lockstep"
