"""Several agents on one plan at once: each works on its first ready step; blocks, hands and the bin are shared."""

import pytest
from test_executive import observe

from semgoal_core.names import agent
from semgoal_planner.executive import Executive
from semgoal_planner.semantic import SemanticPlanner

DESK = ("red", "green", "blue")


def concurrent(scene: str = "desk_cleanup", start: tuple[str, ...] = (), **kwargs) -> Executive:
    ex = Executive(SemanticPlanner(scene), settle_steps=1, **kwargs)
    ex.observe(observe(list(start), scene=scene))
    return ex


def doing(ex: Executive) -> dict[str, str]:
    return {who: str(ex.steps[index].subgoal) for who, index in ex.working.items()}


def test_the_robot_and_a_person_work_at_once_on_independent_turns() -> None:
    """The person claims green's turn while the robot picks blue: their pick is their own hand's (done as it starts),
    their put is active beside the robot's steps, and the plan is confirmed step by step as each agent finishes."""
    ex = concurrent()
    assert ex.set_goal("in_bin(red) & in_bin(green) & in_bin(blue)")[0]
    assert [str(s.subgoal) for s in ex.steps][:4] == ["pick(blue)", "put_in_bin(blue)", "pick(green)", "put_in_bin(green)"]
    ok, message = ex.edit("claim", 2)
    assert ok, message
    assert doing(ex) == {"robot": "pick(blue)", "human": "put_in_bin(green)"}
    assert ex.steps[2].status == "done" and ex.steps[2].assignee == "human"
    ex.observe(observe(["holding(blue)"], 5))
    assert doing(ex) == {"robot": "put_in_bin(blue)", "human": "put_in_bin(green)"}
    assert ex.region_holder("bin") == ("robot", 1)  # the person's drop into the bin waits for the arm
    ex.observe(observe(["holding(blue)", "in_bin(green)"], 8))  # the person was done first
    assert doing(ex) == {"robot": "put_in_bin(blue)"} and ex.contradicted_since is None
    ex.observe(observe(["in_bin(blue)", "in_bin(green)"], 10))
    assert doing(ex) == {"robot": "pick(red)"} and ex.region_holder("bin") is None
    ex.observe(observe(["in_bin(blue)", "in_bin(green)", "holding(red)"], 12))
    ex.observe(observe(["in_bin(blue)", "in_bin(green)", "in_bin(red)"], 14))
    assert ex.status == "succeeded" and ex.replans == 0


def test_in_turns_the_same_claim_waits_for_the_robots_steps() -> None:
    ex = Executive(SemanticPlanner("desk_cleanup"), settle_steps=1, concurrent=False)
    ex.observe(observe([]))
    assert ex.set_goal("in_bin(red) & in_bin(green)")[0] and ex.edit("claim", 3)[0]
    assert doing(ex) == {"robot": "pick(green)"}
    ex.observe(observe(["holding(green)"], 5))
    ex.observe(observe(["in_bin(green)"], 8))
    assert doing(ex) == {"human": "put_in_bin(red)"} and ex.active is None


def test_a_person_carrying_a_block_does_not_contradict_the_plan() -> None:
    """The state never says what a person holds: the robot's rest of the plan is checked with the person's pick
    put back in, so a re-plan does not take the block from them."""
    ex = concurrent()
    assert ex.set_goal("in_bin(red) & in_bin(green)")[0] and ex.edit("claim", 3)[0]
    for step in range(1, 30):
        ex.tick(step)
        ex.observe(observe(["holding(green)"] if step > 3 else [], step))
    assert ex.replans == 0 and ex.contradicted_since is None and doing(ex)["human"] == "put_in_bin(red)"


def test_two_agents_never_work_on_the_same_block() -> None:
    """Three blocks: the person has taken green up to put it by red and away from blue, while the robot's turn moves
    blue next to red: the person's put waits until the robot is done with both."""
    ex = concurrent("three_blocks")
    assert ex.set_goal("close(red,green) & close(red,blue) & ~close(green,blue)")[0]
    assert [str(s.subgoal) for s in ex.steps] == ["pick(blue)", "put_near(blue,red)", "pick(green)",
                                                  "put_near(green,red,not blue)"]
    assert ex.edit("claim", 3)[0]
    assert doing(ex) == {"robot": "pick(blue)"} and ex.steps[2].status == "done"  # the person holds green, waiting
    ex.observe(observe(["holding(blue)"], 5, scene="three_blocks"))
    assert doing(ex) == {"robot": "put_near(blue,red)"}
    ex.observe(observe(["close(red,blue)"], 9, scene="three_blocks"))
    assert doing(ex) == {"human": "put_near(green,red,not blue)"}
    ex.observe(observe(["close(red,blue)", "close(red,green)"], 12, scene="three_blocks"))
    assert ex.status == "succeeded"


def test_the_robots_hand_takes_one_turn_at_a_time() -> None:
    """A hand-over: the robot picked red for the person to bin; its next pick waits until the person took red."""
    ex = concurrent()
    assert ex.set_goal("in_bin(red) & in_bin(green)")[0]
    first = str(ex.steps[0].subgoal)
    assert ex.edit("assign", 1, action="human:alice")[0]
    ex.observe(observe([first.replace("pick", "holding")], 5))
    assert doing(ex) == {"human:alice": str(ex.steps[1].subgoal)}
    ex.observe(observe([str(ex.steps[1].subgoal).replace("put_", "")], 9))
    assert doing(ex) == {"robot": str(ex.steps[2].subgoal)}


def test_claims_and_agents_are_checked() -> None:
    ex = concurrent()
    assert ex.set_goal("in_bin(red) & in_bin(green)")[0]
    refused, reason = ex.edit("claim", 0, action="human:bob")
    assert not refused and "robot's under way" in reason and ex.steps[0].assignee == "robot"
    for bad in ("human:", "robot-arm", "human:a b", ""):
        with pytest.raises(ValueError, match="a named person 'human:NAME'"):
            agent(bad)
        assert not ex.edit("assign", 1, action=bad)[0]
    assert agent(" Human:Alice ") == "human:alice"
    assert ex.edit("claim", 2, action="human:bob")[0]
    assert [s.assignee for s in ex.steps][2:] == ["human:bob", "human:bob"]



def test_two_arms_each_take_a_turn_and_keep_it() -> None:
    """A robot's pick goes to the first free arm, and its put with it; both arms' blocks in hand are put down first when
    the rest of the plan is checked, and a step is confirmed at rest for its own blocks while the other arm holds one."""
    ex = concurrent(robots=("robot", "robot:2"))
    assert ex.set_goal("in_bin(red) & in_bin(green)")[0]
    assert doing(ex) == {"robot": "pick(green)", "robot:2": "pick(red)"}
    assert [s.assignee for s in ex.steps] == ["robot", "robot", "robot:2", "robot:2"]
    ex.observe(observe(["holding(green)", "holding(red)"], 4))
    assert doing(ex) == {"robot": "put_in_bin(green)", "robot:2": "put_in_bin(red)"}
    assert ex.contradicted_since is None
    assert ex.active_for("robot:2") is ex.steps[3] and ex.active is ex.steps[1]
    ex.observe(observe(["in_bin(green)", "holding(red)"], 8))
    assert doing(ex) == {"robot:2": "put_in_bin(red)"} and ex.steps[1].status == "done"
    ex.observe(observe(["in_bin(green)", "in_bin(red)"], 12))
    assert ex.status == "succeeded" and ex.replans == 0


def test_an_arm_takes_the_blocks_it_reaches_first_and_a_step_given_to_it() -> None:
    sides = {"red": ("robot",), "green": ("robot",), "blue": ("robot:2", "robot")}
    ex = concurrent(robots=("robot", "robot:2"), reach=sides.__getitem__)
    assert ex.set_goal("in_bin(red) & in_bin(green) & in_bin(blue)")[0]
    assert doing(ex) == {"robot:2": "pick(blue)", "robot": "pick(green)"}  # the second arm reaches only blue
    ex = concurrent(robots=("robot", "robot:2"), reach=sides.__getitem__)
    assert ex.set_goal("in_bin(red) & in_bin(green)")[0]
    assert doing(ex) == {"robot": "pick(green)"}  # neither block is the second arm's to reach
    ok, message = ex.edit("assign", 2, action="robot:2")
    assert ok, message
    assert doing(ex) == {"robot": "pick(green)", "robot:2": "pick(red)"}


def test_a_step_is_given_only_to_an_arm_at_the_table() -> None:
    ex = concurrent()
    assert ex.set_goal("in_bin(red) & in_bin(green)")[0]
    ok, message = ex.edit("assign", 2, action="robot:2")
    assert not ok and "there is no robot:2 at this table: the arms are robot" in message
    assert all(step.assignee == "robot" for step in ex.steps)


def test_a_robots_step_goes_to_the_hand_its_block_is_in_whatever_the_plans_turns_say() -> None:
    """After a re-plan the done picks of two hands interleave: the world's word on whose hand a block is in wins."""
    hands = {"green": ("robot:2",), "red": ("robot",)}
    ex = concurrent(robots=("robot", "robot:2"), reach=hands.__getitem__)
    assert ex.set_goal("in_bin(red) & in_bin(green)")[0]
    assert doing(ex) == {"robot:2": "pick(green)", "robot": "pick(red)"}
    ex.observe(observe(["holding(green)", "holding(red)"], 4))
    assert doing(ex) == {"robot:2": "put_in_bin(green)", "robot": "put_in_bin(red)"}
