"""The goal-sending retry shared by the operator CLI, the graph client and the tests (no ROS: the action
client is a stand-in whose answers never come for the first ``lost`` goals, as in the Fast DDS
discovery race)."""

from concurrent.futures import Future

from semgoal_sim.ros_interfaces import send_goal


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
