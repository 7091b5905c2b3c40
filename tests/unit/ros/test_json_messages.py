"""ROS messages to and from JSON (the live view's services and channels): every field out, requests in with
every field checked, and a schema that lists the fields with their JSON types."""

import json

import pytest

from semgoal_msgs.msg import Plan, Predicate, SubGoal
from semgoal_msgs.srv import EditPlan
from semgoal_ros.json_messages import json_schema, message_from_dict, message_to_dict


def test_a_plan_goes_out_whole_and_as_json() -> None:
    plan = Plan(goal="in_bin(red)", status="executing", revision=3, current=1, steps=[
        SubGoal(index=0, action="pick(red)", goal=[Predicate(name="holding", args=["red"], value=True)]),
        SubGoal(index=1, action="put_in_bin(red)", assignee="human")])
    data = json.loads(json.dumps(message_to_dict(plan)))
    assert data["steps"][0]["goal"][0] == {"name": "holding", "args": ["red"], "value": True}
    assert data["steps"][1]["assignee"] == "human" and data["revision"] == 3
    assert set(data["header"]) == {"stamp", "frame_id"}


def test_a_request_is_built_from_json_with_every_field_checked() -> None:
    request = message_from_dict(EditPlan.Request, {"op": "move", "index": 2, "to_index": 0, "request_id": "a"})
    assert (request.op, request.index, request.to_index, request.action, request.request_id) == ("move", 2, 0, "", "a")
    for bad, field in (({"op": "remove", "idx": 1}, "idx"), ({"op": "remove", "index": -1}, "index"),
                       ({"op": "remove", "index": "two"}, "index"), ({"op": 5}, "op"),
                       ({"op": "remove", "index": 2 ** 40}, "index")):
        with pytest.raises(ValueError, match=field):
            message_from_dict(EditPlan.Request, bad)
    with pytest.raises(ValueError, match="JSON object"):
        message_from_dict(EditPlan.Request, ["remove"])


def test_the_schema_names_every_field_with_its_json_type() -> None:
    schema = json_schema(EditPlan.Request)
    assert set(schema["properties"]) == set(EditPlan.Request.get_fields_and_field_types())
    assert schema["properties"]["index"]["type"] == "integer" and schema["properties"]["op"]["type"] == "string"
    plan = json_schema(Plan)
    assert plan["properties"]["steps"]["type"] == "array"
    assert plan["properties"]["header"]["properties"]["stamp"]["properties"]["sec"]["type"] == "integer"
