"""The request retry (goals, service calls) shared by the operator CLI, the graph client and the tests,
and the planner's memory of edit answers (no ROS: the action client is a stand-in whose answers never
come for the first ``lost`` goals, as in the Fast DDS discovery race)."""

from concurrent.futures import Future

import pytest

from semgoal_ros.interfaces import RecentAnswers, ReusedRequestIdError, run_node, send_goal, send_until_answered


class LosingAction:
    def __init__(self, lost: int) -> None:
        self.lost, self.sent = lost, []

    def send_goal_async(self, goal, feedback_callback=None) -> Future:
        self.sent.append(goal)
        future = Future()
        if len(self.sent) > self.lost:
            future.set_result(f"handle {len(self.sent)}")
        return future


def no_wait(condition, timeout: float) -> bool:
    return condition()


def test_a_lost_answer_is_sent_again_until_one_comes() -> None:
    action = LosingAction(lost=2)
    assert send_goal(action, "goal", no_wait, attempts=3) == "handle 3"
    assert action.sent == ["goal"] * 3


def test_an_answered_goal_is_sent_once() -> None:
    action = LosingAction(lost=0)
    assert send_goal(action, "goal", no_wait) == "handle 1" and len(action.sent) == 1


def test_no_answer_after_every_attempt_gives_none() -> None:
    action = LosingAction(lost=5)
    assert send_goal(action, "goal", no_wait, attempts=3) is None and len(action.sent) == 3


def test_a_service_call_is_sent_again_like_a_goal() -> None:
    answered = Future()
    answered.set_result("response")
    sent = iter([Future(), answered])
    assert send_until_answered(lambda: next(sent), no_wait, attempts=3) == "response"


def test_recent_answers_repeat_an_answer_by_request_id_and_forget_the_oldest() -> None:
    recent = RecentAnswers(size=2)
    recent.remember("a", 1)
    recent.remember("b", 2)
    assert recent.get("a") == 1 and recent.get("b") == 2
    recent.remember("c", 3)
    assert recent.get("a") is None and recent.get("c") == 3


def test_a_request_id_is_bound_to_its_request() -> None:
    """A reused request id returned the old answer for a different edit."""
    recent = RecentAnswers()
    recent.remember("id-1", "removed step 2", ("remove", 2))
    assert recent.get("id-1", ("remove", 2)) == "removed step 2"
    with pytest.raises(ReusedRequestIdError, match="was used for another request"):
        recent.get("id-1", ("remove", 3))


def test_requests_without_an_id_are_never_remembered() -> None:
    recent = RecentAnswers()
    recent.remember("", "answer")
    assert recent.get("") is None and not recent.answers


@pytest.mark.slow
def test_run_node_stops_cleanly_when_interrupted_while_a_node_is_built() -> None:
    """A SIGINT while a node creates its servers invalidates the context and rcl raises from the constructor
    (seen in CI as "Failed to create action server: rcl node's context is invalid"): a clean stop, exit 0."""
    import rclpy



    class InterruptedWhileBuilt:
        def __init__(self) -> None:
            rclpy.shutdown()  # what the SIGINT handler does
            raise ValueError("Failed to create action server: rcl node's context is invalid")

    run_node(InterruptedWhileBuilt, [])
    assert not rclpy.ok()

    class Broken:
        def __init__(self) -> None:
            raise ValueError("a real error while the context is fine")

    with pytest.raises(ValueError, match="a real error"):
        run_node(Broken, [])
    rclpy.try_shutdown()
