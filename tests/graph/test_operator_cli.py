"""The operator's commands against the four node processes, as an operator types them in a second shell:
`./semgoal plan show`, `./semgoal goal ... --wait [--max-steps N]` and a refused plan edit. Each exits 0
on success and 1 with the reason otherwise."""

import subprocess

from conftest import ROOT, NodeProcesses
from semgoal_bringup.graph import NODES, node_params

TASK, SEED = "MC-2", 3_000_000


def semgoal(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(ROOT / "semgoal"), *args], capture_output=True, text=True, timeout=120)


def test_operator_commands_drive_the_graph(nodes: NodeProcesses) -> None:
    params = node_params(TASK, SEED, "lockstep")
    for package, exe in NODES:
        nodes.start(package, exe, params=params[exe])

    shown = semgoal("plan", "show")
    assert shown.returncode == 1 and "status: empty" in shown.stdout, shown.stdout + shown.stderr

    unknown = semgoal("goal", "in_bin(red)", "--wait")  # two_blocks has no bin
    assert unknown.returncode == 1 and "in_bin" in unknown.stdout, unknown.stdout + unknown.stderr

    short = semgoal("goal", TASK, "--wait", "--max-steps", "3")
    assert short.returncode == 1, short.stdout + short.stderr
    assert "budget of 3 control steps" in short.stdout and "(3 control steps" in short.stdout, short.stdout

    solved = semgoal("goal", TASK, "--wait", "--max-steps", "600")
    assert solved.returncode == 0 and solved.stdout.strip().splitlines()[-1].startswith("success"), solved.stdout

    refused = semgoal("plan", "remove", "0")
    assert refused.returncode == 1 and "refused: no plan to edit (plan is succeeded)" in refused.stdout, refused.stdout


def test_max_steps_needs_the_action_and_a_count() -> None:
    assert semgoal("goal", TASK, "--max-steps", "5").returncode == 2  # the goal topic carries no budget
    assert semgoal("goal", TASK, "--wait", "--max-steps", "-1").returncode == 2


def test_a_plan_revision_must_fit_the_message() -> None:
    for revision in ("-1", str(2**32)):
        out = semgoal("plan", "pause", "--revision", revision)
        assert out.returncode == 2 and "--revision must be 0 or a plan revision" in out.stderr, out.stderr
