"""The operator's commands against the four node processes, as an operator types them in a second shell:
`./semgoal plan show`, `./semgoal goal ... --wait [--max-steps N]` and a refused plan edit. Each exits 0
on success and 1 with the reason otherwise."""

import subprocess

from conftest import ROOT, GraphProbe, NodeProcesses
from semgoal_bringup.graph import NODES, node_params
from semgoal_core import names
from semgoal_msgs.msg import Plan
from semgoal_ros import interfaces as topics

TASK, SEED = "MC-2", 3_000_000


def semgoal(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(semgoal_command(*args), capture_output=True, text=True, timeout=120)


def semgoal_command(*args: str) -> list[str]:
    return [str(ROOT / "semgoal"), *args]


def test_operator_commands_drive_the_graph(nodes: NodeProcesses, probe: GraphProbe) -> None:
    params = node_params(TASK, SEED, "lockstep")
    params["planner_node"]["state_wait_s"] = 60.0
    world_nodes = [node for node in NODES if node[1] in ("sim_node", "predicate_node")]
    for package, exe in NODES:
        if (package, exe) not in world_nodes:
            nodes.start(package, exe, params=params[exe])

    shown = semgoal("plan", "show")
    assert shown.returncode == 1 and "status: empty" in shown.stdout, shown.stdout + shown.stderr

    # refused from the scene's vocabulary alone, before any world state exists
    unknown = semgoal("goal", "in_bin(red)", "--wait")  # two_blocks has no bin
    assert unknown.returncode == 1 and "in_bin" in unknown.stdout, unknown.stdout + unknown.stderr

    # a goal sent before the world is up waits for its first state, then runs (into a tiny budget)
    early = subprocess.Popen(semgoal_command("goal", TASK, "--wait", "--max-steps", "3"),
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    assert probe.poll(lambda: "waits up to 60 s for a semantic state" in nodes.logs(), timeout=60), nodes.logs()
    for package, exe in world_nodes:
        nodes.start(package, exe, params=params[exe])
    out, _ = early.communicate(timeout=120)
    assert early.returncode == 1, out
    assert "budget of 3 control steps" in out and "(3 control steps" in out, out

    solved = semgoal("goal", TASK, "--wait", "--max-steps", "600")
    assert solved.returncode == 0 and solved.stdout.strip().splitlines()[-1].startswith("success"), solved.stdout
    shown = semgoal("plan", "show").stdout.splitlines()  # the plan says why it ended
    assert "status: succeeded" in shown[0] and shown[1].startswith("last: goal ") and shown[1].endswith("holds at rest"), shown

    for bad in ("DC-9", "put purple in the bin"):  # on the topic: refused with the reason, not "published"
        out = semgoal("goal", bad)
        assert out.returncode == 2 and "refused" in out.stderr, out.stdout + out.stderr
    sentence = semgoal("goal", "put red near green")
    assert sentence.returncode == 0 and "published goal" in sentence.stdout, sentence.stdout + sentence.stderr

    refused = semgoal("plan", "remove", "0")
    assert refused.returncode == 1 and refused.stdout.startswith("refused: "), refused.stdout


def test_a_goal_on_the_topic_before_the_world_is_up_waits_for_it(nodes: NodeProcesses, probe: GraphProbe) -> None:
    """`ros2 topic pub` of a goal as the nodes start: planned once the first semantic state comes, not refused."""
    params = node_params(TASK, SEED, "lockstep")
    params["planner_node"]["state_wait_s"] = 60.0
    nodes.start("semgoal_planner", "planner_node", params=params["planner_node"])
    plans: list[Plan] = []
    probe.node.create_subscription(Plan, topics.PLAN, plans.append, topics.LATCHED)
    sent = semgoal("goal", TASK)
    assert sent.returncode == 0 and "published goal" in sent.stdout, sent.stdout + sent.stderr
    assert probe.poll(lambda: "waits up to 60 s for a semantic state" in nodes.logs(), timeout=60), nodes.logs()
    for exe in ("sim_node", "predicate_node"):
        nodes.start("semgoal_sim", exe, params=params[exe])
    probe.spin_until(lambda: plans and plans[-1].steps, 60, "the plan of the early goal")
    assert plans[-1].status == names.PlanStatus.EXECUTING, nodes.logs()


def test_max_steps_needs_the_action_and_a_count() -> None:
    assert semgoal("goal", TASK, "--max-steps", "5").returncode == 2  # the goal topic carries no budget
    assert semgoal("goal", TASK, "--wait", "--max-steps", "-1").returncode == 2


def test_a_plan_revision_must_fit_the_message() -> None:
    for revision in ("-1", str(2**32)):
        out = semgoal("plan", "pause", "--revision", revision)
        assert out.returncode == 2 and "--revision must be 0 or a plan revision" in out.stderr, out.stderr
