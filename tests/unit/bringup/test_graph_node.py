"""graph_node's command line: which nodes it composes, under which namespace, with which values of their own."""

import pytest
from rclpy.parameter import Parameter

from semgoal_bringup.composed import node_factories, parameter_overrides, split_entry


def test_an_entry_names_its_namespace_before_the_executable():
    assert split_entry("policy_node") == ("", "policy_node")
    assert split_entry("robot2/policy_node") == ("/robot2", "policy_node")
    assert split_entry(" /robot2/policy_node ") == ("/robot2", "policy_node")


def test_a_param_is_read_as_ros_reads_a_value_and_kept_to_its_node():
    overrides = parameter_overrides(["robot2/policy_node:arm:=2", "robot2/policy_node:model_dir:=",
                                     "robot2/policy_node:rate_hz:=12.5", "robot2/policy_node:scene:=desk_cleanup"],
                                    ["policy_node", "robot2/policy_node"])
    assert overrides["policy_node"] == []
    values = {p.name: (p.type_, p.value) for p in overrides["robot2/policy_node"]}
    assert values == {"arm": (Parameter.Type.INTEGER, 2), "model_dir": (Parameter.Type.STRING, ""),
                      "rate_hz": (Parameter.Type.DOUBLE, 12.5), "scene": (Parameter.Type.STRING, "desk_cleanup")}


@pytest.mark.parametrize("setting", ["robot3/policy_node:arm:=2", "robot2/policy_node:arm=2", "robot2/policy_node:=2"])
def test_a_param_of_no_node_or_not_so_written_is_refused_with_the_form(setting):
    with pytest.raises(ValueError, match="NS/EXE:KEY:=VALUE"):
        parameter_overrides([setting], ["policy_node", "robot2/policy_node"])


def test_each_entry_makes_its_node_class_with_its_namespace_and_values():
    plain, second = node_factories(["policy_node", "robot2/policy_node"], ["robot2/policy_node:arm:=2"])
    assert plain.func is second.func and plain.func.__name__ == "PolicyNode"
    assert plain.keywords == {}
    assert second.keywords["namespace"] == "/robot2"
    assert [(p.name, p.value) for p in second.keywords["parameter_overrides"]] == [("arm", 2)]
