"""planner_node in its own process: the test plays the predicates node (semantic states) and the
operator (goals, plan edits, the ExecuteGoal action) and checks the plan and sub-goal topics."""

from rclpy.action import ActionClient

from conftest import GraphProbe, NodeProcesses, semantic_state
from semgoal_core.settling import SETTLE_STEPS
from semgoal_msgs.action import ExecuteGoal
from semgoal_msgs.msg import GoalRequest, Plan, SemanticState, SubGoal
from semgoal_msgs.srv import EditPlan, GetPlan
from semgoal_ros import interfaces as topics


class Operator:
    def __init__(self, probe: GraphProbe) -> None:
        self.probe = probe
        self.plans: list[Plan] = []
        self.subgoals: list[SubGoal] = []
        node = probe.node
        node.create_subscription(Plan, topics.PLAN, self.plans.append, topics.LATCHED)
        node.create_subscription(SubGoal, topics.SUBGOAL, self.subgoals.append, topics.LATCHED)
        self.states = node.create_publisher(SemanticState, topics.SEMANTIC_STATE, topics.PER_STEP)
        self.goals = node.create_publisher(GoalRequest, topics.GOAL, 10)

    def call(self, service_type, name, request):
        client = self.probe.node.create_client(service_type, name)
        self.probe.spin_until(client.service_is_ready, 30, name)
        return self.probe.spin_future(client.call_async(request), 30, name)

    def edit(self, op: str, index: int = 0, to_index: int = 0, action: str = "", **fields) -> EditPlan.Response:
        return self.call(EditPlan, topics.EDIT_PLAN,
                         EditPlan.Request(op=op, index=index, to_index=to_index, action=action, **fields))

    def observe(self, true: set[str], step: int, held: bool = True, fallen: tuple[str, ...] = ()) -> None:
        """The world as the predicates would report it at ``step`` (and, ``held``, long enough after it to
        confirm a robot step)."""
        for at in (step, step + SETTLE_STEPS - 1)[: 2 if held else 1]:
            self.states.publish(semantic_state(true, at, fallen))
            self.probe.spin_for(0.3)

    def actions(self) -> list[str]:
        return [s.action for s in self.plans[-1].steps]


def test_goal_plan_edits_and_subgoals(nodes: NodeProcesses, probe: GraphProbe) -> None:
    nodes.start("semgoal_planner", "planner_node", params={"scene": "desk_cleanup"})
    op = Operator(probe)
    probe.spin_until(lambda: op.plans and op.subgoals, 30, "latched plan and sub-goal")
    assert op.plans[-1].status == "empty" and op.subgoals[-1].status == "empty"
    probe.spin_until(lambda: op.states.get_subscription_count() > 0, 20, "planner subscribed")
    op.observe(set(), 0)

    op.goals.publish(GoalRequest(task="", literals=["in_bin(purple)"]))  # bad goal: refused, node lives on
    op.goals.publish(GoalRequest(task="DC-3"))
    probe.spin_until(lambda: op.plans[-1].status == "executing", 20, "plan for DC-3")
    assert op.actions() == ["pick(blue)", "put_in_bin(blue)", "pick(green)", "put_in_bin(green)", "pick(red)", "put_in_bin(red)"]
    probe.spin_until(lambda: op.subgoals[-1].action == "pick(blue)", 10, "active sub-goal")
    assert op.subgoals[-1].status == "active"
    assert [(p.name, list(p.args), p.value) for p in op.subgoals[-1].goal] == [("holding", ["blue"], True)]

    refused = op.edit("remove", 0)
    assert not refused.success and "cannot run" in refused.message
    assert [s.action for s in refused.plan.steps] == op.actions()
    assert not op.edit("insert", 1, action="fly(red)").success
    moved = op.edit("move", 2, 0)  # pick(green) first, then put_in_bin(blue) cannot run
    assert not moved.success
    swapped = op.edit("replace", 0, action="pick(red)")
    assert not swapped.success  # put_in_bin(blue) would then need holding(blue)
    reordered = [op.edit("replace", 4, action="pick(blue)"), op.edit("replace", 0, action="pick(red)")]
    assert not reordered[0].success and not reordered[1].success
    handover = op.edit("assign", 0, action="human")  # a pick asks the robot's hand to hold: never a person's
    assert not handover.success and "a person cannot do" in handover.message
    assert op.edit("assign", 1, action="human").success
    assert op.edit("pause").success
    probe.spin_until(lambda: op.subgoals[-1].status == "paused", 10, "paused sub-goal")
    assert op.edit("resume").success

    op.observe({"holding(blue)"}, 20)  # the pick is done: the put is the person's
    probe.spin_until(lambda: op.subgoals[-1].status == "waiting_for_human", 10, "human step")
    assert op.edit("assign", 1, action="robot").success
    probe.spin_until(lambda: op.subgoals[-1].action == "put_in_bin(blue)", 10, "next sub-goal")
    shown = op.call(GetPlan, topics.GET_PLAN, GetPlan.Request())
    assert shown.success and shown.plan.current == 1 and shown.plan.steps[0].status == "done"

    stale = op.edit("pause", revision=shown.plan.revision - 1)  # made before the pick was done
    assert not stale.success and "revision" in stale.message and stale.plan.status == "executing"
    first, again = (op.edit("pause", revision=shown.plan.revision, request_id="operator-1") for _ in range(2))
    assert first.success and again.success and again.message == first.message  # answered again, applied once
    assert again.plan.revision == first.plan.revision and again.plan.status == "paused"
    assert not op.edit("pause", request_id="operator-2").success  # a new request: already paused
    reused = op.edit("resume", request_id="operator-1")  # another edit under a used id: refused, plan as it is
    assert not reused.success and "was used for another request" in reused.message and reused.plan.status == "paused"


def test_execute_goal_action_succeeds_and_reports(nodes: NodeProcesses, probe: GraphProbe) -> None:
    nodes.start("semgoal_planner", "planner_node", params={"scene": "desk_cleanup"})
    op = Operator(probe)
    probe.spin_until(lambda: op.states.get_subscription_count() > 0, 30, "planner subscribed")
    op.observe(set(), 0, held=False)
    client = ActionClient(probe.node, ExecuteGoal, topics.EXECUTE_GOAL)
    probe.spin_until(client.server_is_ready, 20, "execute_goal server")
    goal = ExecuteGoal.Goal()
    goal.goal.literals = ["in_bin(red)"]
    feedback = []
    handle = probe.send_goal(client, goal, feedback.append)
    result_future = handle.get_result_async()
    probe.spin_until(lambda: op.plans and op.plans[-1].status == "executing", 10, "plan executing")
    assert op.actions() == ["pick(red)", "put_in_bin(red)"]
    op.observe({"holding(red)"}, 25)
    op.observe({"in_bin(red)"}, 50)
    result = probe.spin_future(result_future, 20, "action result").result
    assert result.success and "holds" in result.message
    settled = 50 + SETTLE_STEPS - 1  # the goal holds from step 50; at rest over SETTLE_STEPS steps
    assert result.control_steps == settled and abs(result.sim_time - settled * 0.04) < 1e-9 and result.replans == 0
    assert feedback and feedback[-1].feedback.plan.steps

    bad = ExecuteGoal.Goal()
    bad.goal.task = "MC-2"  # wrong scene: refused with the reason
    handle = probe.send_goal(client, bad)
    result = probe.spin_future(handle.get_result_async(), 20, "action result").result
    assert not result.success and "runs in scene two_blocks" in result.message
    assert (result.control_steps, result.replans, result.sim_time) == (0, 0, 0.0)  # not the last goal's figures

    cancel_goal = ExecuteGoal.Goal()
    cancel_goal.goal.literals = ["in_bin(green)"]
    handle = probe.send_goal(client, cancel_goal)
    probe.spin_for(0.3)
    probe.spin_future(handle.cancel_goal_async(), 10, "cancel")
    result = probe.spin_future(handle.get_result_async(), 20, "cancelled result").result
    assert not result.success and result.message == "cancelled"

    first, second = ExecuteGoal.Goal(), ExecuteGoal.Goal()
    first.goal.literals, second.goal.literals = ["in_bin(blue)"], ["holding(green)"]
    first_handle = probe.send_goal(client, first)
    probe.spin_until(lambda: "put_in_bin(blue)" in op.actions(), 10, "first goal planned")
    second_handle = probe.send_goal(client, second)
    result = probe.spin_future(first_handle.get_result_async(), 20, "superseded result").result
    assert not result.success and "superseded" in result.message
    probe.spin_until(lambda: op.actions() == ["pick(green)"], 10, "second goal planned")
    op.observe({"holding(green)"}, 80)
    result = probe.spin_future(second_handle.get_result_async(), 20, "second result").result
    assert result.success and result.replans == 0

    op.observe(set(), 85, held=False)  # green put down again
    lost = ExecuteGoal.Goal()
    lost.goal.literals = ["in_bin(blue)"]
    handle = probe.send_goal(client, lost)
    probe.spin_until(lambda: op.actions() == ["pick(blue)", "put_in_bin(blue)"], 10, "goal planned")
    op.observe(set(), 90, held=False, fallen=("blue",))  # blue fell off the table: no re-plan can help
    result = probe.spin_future(handle.get_result_async(), 20, "fallen-block result").result
    assert not result.success and result.replans == 0
    assert result.message == "blue fell off the table, out of the arm's reach: step 0 pick(blue) cannot be done"


def test_a_sentence_on_the_goal_topic_is_planned_and_achieved(nodes: NodeProcesses, probe: GraphProbe) -> None:
    """`ros2 topic pub /semgoal/goal ... "{text: 'put the red block in the bin'}"`: the plan's goal shows the
    literals the sentence became; an ambiguous sentence is refused and the plan stays."""
    nodes.start("semgoal_planner", "planner_node", params={"scene": "desk_cleanup"})
    op = Operator(probe)
    probe.spin_until(lambda: op.states.get_subscription_count() > 0, 30, "planner subscribed")
    op.observe(set(), 0, held=False)
    op.goals.publish(GoalRequest(text="please put the red block in the bin"))
    probe.spin_until(lambda: op.plans and op.plans[-1].status == "executing", 20, "plan for the sentence")
    assert op.plans[-1].goal == "in_bin(red)" and op.actions() == ["pick(red)", "put_in_bin(red)"]
    op.goals.publish(GoalRequest(text="put it in the bin"))  # which block? refused, the plan stays
    probe.spin_for(1.0)
    assert op.plans[-1].goal == "in_bin(red)" and op.plans[-1].status == "executing"
    op.observe({"holding(red)"}, 20)
    op.observe({"in_bin(red)"}, 40)
    probe.spin_until(lambda: op.plans[-1].status == "succeeded", 20, "goal achieved at rest")


def test_ctrl_c_on_goal_wait_cancels_the_goal(nodes: NodeProcesses, probe: GraphProbe) -> None:
    """Ctrl-C on `./semgoal goal ... --wait` left the goal running; now it cancels it, exit 130."""
    import signal
    import subprocess

    from conftest import ROOT

    nodes.start("semgoal_planner", "planner_node", params={"scene": "desk_cleanup"})
    op = Operator(probe)
    probe.spin_until(lambda: op.states.get_subscription_count() > 0, 30, "planner subscribed")
    op.observe(set(), 0, held=False)
    waiting = subprocess.Popen([str(ROOT / "semgoal"), "goal", "in_bin(red)", "--wait"], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    probe.spin_until(lambda: op.plans and op.plans[-1].status == "executing", 30, "goal executing")
    waiting.send_signal(signal.SIGINT)
    _, err = waiting.communicate(timeout=30)
    assert waiting.returncode == 130 and "the goal was cancelled" in err, err
    probe.spin_until(lambda: op.plans[-1].status == "failed", 10, "goal cancelled")


def test_a_world_gone_silent_or_started_again_fails_the_goal_with_the_reason(nodes: NodeProcesses, probe: GraphProbe) -> None:
    nodes.start("semgoal_planner", "planner_node", params={"scene": "desk_cleanup", "world_silence_s": 1.5})
    op = Operator(probe)
    action = ActionClient(probe.node, ExecuteGoal, topics.EXECUTE_GOAL)
    probe.spin_until(lambda: op.states.get_subscription_count() > 0 and action.server_is_ready(), 30, "the planner")

    def state_at(step: int, sim_time: float) -> SemanticState:
        msg = semantic_state(set(), step)
        msg.header.stamp.sec, msg.header.stamp.nanosec = int(sim_time), int(sim_time % 1 * 1e9)
        return msg

    op.states.publish(state_at(100, 4.0))
    handle = probe.send_goal(action, ExecuteGoal.Goal(goal=GoalRequest(task="DC-3")))
    op.states.publish(state_at(101, 4.04))
    op.states.publish(state_at(1, 0.04))  # a new sim's clock: back at the start
    result = probe.spin_future(handle.get_result_async(), 10, "the goal's end").result
    assert not result.success and "the world started again (sim time 0.04 s after 4.04 s" in result.message, result.message

    handle = probe.send_goal(action, ExecuteGoal.Goal(goal=GoalRequest(task="DC-3")))
    op.states.publish(state_at(2, 0.08))  # then nothing: the sim (or the predicates) gone
    result = probe.spin_future(handle.get_result_async(), 10, "the goal's end").result
    assert not result.success and "no semantic state for 1." in result.message, result.message
