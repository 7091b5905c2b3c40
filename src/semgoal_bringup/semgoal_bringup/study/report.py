"""`./semgoal study report DIR`: one table per participant and one across participants, as CSV and Markdown, in
``DIR/report/``. Per condition: episodes, success, the fluency measures from the recordings (the mean of each
episode's, :mod:`semgoal_bringup.study.fluency`) and the questionnaires' scores; across participants the mean and
standard deviation of each, with how many participants had a value."""

from __future__ import annotations

import argparse
import csv
import json
import statistics
import sys
from pathlib import Path

from semgoal_bringup.study.fluency import MEASURES, recording_fluency
from semgoal_bringup.study.session import SESSION_FILE

COLUMNS = ("episodes", "success", "task_time_s", *MEASURES, "nasa-tlx", "sus")


def participant_rows(folder: Path) -> list[dict]:
    """A row per condition the participant ran, in the order they ran them."""
    session = json.loads((folder / SESSION_FILE).read_text())
    rows = []
    for position, name in enumerate(session["order"]):
        outcomes = [o for o in session["outcomes"] if o["position"] == position]
        answers = {a["questionnaire"]: a["score"] for a in session["answers"] if a["position"] == position}
        if not outcomes and not answers:
            continue
        measured = [recording_fluency(folder / o["recording"]) for o in outcomes
                    if o["recording"] and (folder / o["recording"]).exists()]
        row = {"participant": session["participant"], "order": position + 1, "condition": name,
               "episodes": len(outcomes), "success": _mean([float(o["success"]) for o in outcomes]),
               "task_time_s": _mean([f.task_time for f in measured]),
               **{m: _mean([getattr(f, m) for f in measured]) for m in MEASURES},
               "nasa-tlx": answers.get("nasa-tlx"), "sus": answers.get("sus")}
        rows.append(row)
    return rows


def across(rows: list[dict]) -> list[dict]:
    """Per condition: mean, standard deviation and count over the participants with a value."""
    table = []
    for condition in dict.fromkeys(r["condition"] for r in rows):
        mine = [r for r in rows if r["condition"] == condition]
        row = {"condition": condition, "participants": len({r["participant"] for r in mine})}
        for column in COLUMNS:
            values = [r[column] for r in mine if r[column] is not None]
            row[f"{column}_mean"] = _mean(values)
            row[f"{column}_sd"] = statistics.stdev(values) if len(values) > 1 else None
            row[f"{column}_n"] = len(values)
        table.append(row)
    return table


def write_table(rows: list[dict], stem: Path) -> None:
    """``stem``.csv and ``stem``.md."""
    if not rows:
        return
    columns = list(rows[0])
    with stem.with_suffix(".csv").open("w", newline="") as stream:
        writer = csv.DictWriter(stream, columns)
        writer.writeheader()
        writer.writerows({k: _text(v) for k, v in row.items()} for row in rows)
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(_text(row[c]) for c in columns) + " |" for row in rows]
    stem.with_suffix(".md").write_text("\n".join(lines) + "\n")


def _mean(values: list[float]) -> float | None:
    return statistics.fmean(values) if values else None


def _text(value) -> str:
    if value is None:
        return ""
    return f"{value:.3f}" if isinstance(value, float) else str(value)


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal study report", description=__doc__.split("\n\n")[0])
    parser.add_argument("dir", type=Path, help="the study's folder (study run --out)")
    args = parser.parse_args(argv)
    folders = sorted(p.parent for p in args.dir.glob(f"*/{SESSION_FILE}"))
    if not folders:
        parser.error(f"no participant's session in {args.dir} (a folder per participant with {SESSION_FILE})")
    out = args.dir / "report"
    out.mkdir(exist_ok=True)
    everyone = []
    for folder in folders:
        rows = participant_rows(folder)
        write_table(rows, out / folder.name)
        everyone += rows
        print(f"{folder.name}: {len(rows)} condition(s) -> {out / folder.name}.csv, .md")
    write_table(across(everyone), out / "all")
    print(f"across {len(folders)} participant(s) -> {out / 'all'}.csv, .md")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
