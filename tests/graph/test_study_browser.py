"""Study mode end to end in a real browser (Debian's headless Chromium) on real nodes: `./semgoal study run` with a
two-condition protocol. In the first the robot works alone (a claim is refused); in the second the participant
claims a step while the robot works, does it in the page, and the plan succeeds. After each condition they answer
the raw NASA-TLX and the SUS. `./semgoal study report` then has the fluency measures from the recordings and the
answers' scores."""

import csv
import os
from pathlib import Path

from selenium.common.exceptions import StaleElementReferenceException
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait
from test_console_browser import SCREENSHOTS, TOKEN, browser, click_now, drop_in_bin, start_page  # noqa: F401 (the fixture)

from conftest import NodeProcesses, free_port
from semgoal_bringup.study import report

PROTOCOL = """
name: together or alone
conditions:
  - name: robot alone
    people: false
    goals: [{world: DC-3, seed: 6, goal: DC-3}]
  - name: at once
    goals: [{world: DC-3, seed: 6, goal: put every block in the bin}]
"""
TLX = {"mental": 30, "physical": 10, "temporal": 45, "performance": 20, "effort": 35, "frustration": 5}
SUS = {f"q{i}": 4 if i % 2 else 2 for i in range(1, 11)}
"""Answers whose scores are known: raw TLX 24.17, SUS 75."""
LAST_STEP_OPEN = "#plan-steps li[data-index='5']:not(.done) button.claim:not([disabled])"
"""The last step's claim of a plan still to do: the first condition's plan, all done, has six steps too (its claim
buttons disabled), and may still be drawn when the second condition's goal is named."""


def start_study(nodes: NodeProcesses, protocol: Path, out: Path, port: int) -> None:
    command = ["./semgoal", "study", "run", str(protocol), "--participant", "P01", "--out", str(out),
               "--port", str(port), "--token", TOKEN]
    start_page(nodes, "study run", command, port, out.parent / "study.log", wait_s=60)


def test_a_participant_runs_a_two_condition_protocol(nodes: NodeProcesses, browser, tmp_path: Path) -> None:  # noqa: F811
    protocol, out, port = tmp_path / "protocol.yaml", tmp_path / "results", free_port()
    protocol.write_text(PROTOCOL)
    shots = SCREENSHOTS if os.environ.get("SEMGOAL_SCREENSHOTS") == "1" else tmp_path
    shots.mkdir(parents=True, exist_ok=True)
    start_study(nodes, protocol, out, port)
    wait = WebDriverWait(browser, 120, ignored_exceptions=(StaleElementReferenceException,))
    browser.get(f"http://127.0.0.1:{port}/?token={TOKEN}")

    def where() -> str:
        return browser.find_element(By.ID, "study-where").text

    def click(selector: str) -> None:
        click_now(browser, selector)

    def answer(values: dict[str, int]) -> None:
        for key, value in values.items():
            radio = browser.find_elements(By.CSS_SELECTOR, f"#study-form input[name='{key}'][value='{value}']")
            if radio:
                radio[0].click()
            else:
                browser.execute_script("const r = document.querySelector(`#study-form input[name='${arguments[0]}']`);"
                                       "r.value = arguments[1]; r.dispatchEvent(new Event('input'));", key, value)
        click("#study-form button.save-answers")

    def questionnaires(title: str) -> None:
        wait.until(lambda b: "is over" in where() and "NASA" in b.find_element(By.ID, "study-form").text)
        browser.save_screenshot(str(shots / "study-questionnaire.png"))
        answer(TLX)
        wait.until(lambda b: "System Usability" in b.find_element(By.ID, "study-form").text)
        answer(SUS)
        wait.until(lambda b: title in where())

    wait.until(lambda b: "Condition 1 of 2: robot alone" in where() and "Press Start" in where())
    click("#study-start")
    wait.until(lambda b: "Goal 1 of 1: DC-3" in where() and b.find_elements(By.CSS_SELECTOR, LAST_STEP_OPEN))
    click(LAST_STEP_OPEN)
    wait.until(lambda b: "the robot works alone" in b.find_element(By.ID, "message").text)
    questionnaires("Condition 2 of 2: at once")

    click("#study-start")
    wait.until(lambda b: "put every block in the bin" in where() and b.find_elements(By.CSS_SELECTOR, LAST_STEP_OPEN))
    click(LAST_STEP_OPEN)  # the last block's turn, while the robot does the first
    wait.until(lambda b: "you put_in_bin(" in b.find_element(By.ID, "doing").text
               and "robot " in b.find_element(By.ID, "doing").text)
    block = browser.find_element(By.ID, "human-action").text.removeprefix("put_in_bin(").rstrip(")")
    browser.save_screenshot(str(shots / "study-at-once.png"))
    drop_in_bin(browser, block)
    questionnaires("The study is over")

    assert report.main([str(out)]) == 0
    print((out / "report" / "P01.md").read_text())
    rows = {row["condition"]: row for row in csv.DictReader((out / "report" / "P01.csv").open())}
    assert list(rows) == ["robot alone", "at once"] and all(r["success"] == "1.000" for r in rows.values())
    alone, together = rows["robot alone"], rows["at once"]
    assert float(alone["human_idle"]) == 1.0 and float(alone["concurrent_activity"]) == 0.0
    assert float(together["concurrent_activity"]) > 0 and float(together["human_idle"]) < 1.0
    assert all(0 <= float(r[m]) <= 1 for r in rows.values() for m in report.MEASURES)
    assert {r["nasa-tlx"] for r in rows.values()} == {"24.167"} and {r["sus"] for r in rows.values()} == {"75.000"}
    overall = list(csv.DictReader((out / "report" / "all.csv").open()))
    assert [r["condition"] for r in overall] == ["robot alone", "at once"] and overall[0]["participants"] == "1"
    assert len(list((out / "P01").glob("*.mcap"))) == 2 and (out / "P01" / "answers.csv").exists()
