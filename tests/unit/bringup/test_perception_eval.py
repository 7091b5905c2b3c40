"""`./semgoal eval perception` at a tiny size: the shipped voter and the paper's literal network both load and are
measured on the same held-out frames (the literal network had stopped loading once the tabletop's literals came); the
tabletop's frames are measured by the voter alone (the literal network knows the paper's scenes)."""

import json

from semgoal_bringup.experiments import perception_eval


def test_eval_perception_measures_the_voter_and_the_literal_network_on_a_few_frames(tmp_path, capsys):
    assert perception_eval.main(["--frames", "6", "--conditions", "nominal", "--cache", str(tmp_path), "--json"]) == 0
    nominal = json.loads(capsys.readouterr().out)["nominal"]
    assert nominal["frames"] == 6 and nominal["poses"]["blocks"] > 0
    assert nominal["literals"]["overall"]["total"] > 0
    assert nominal["literals_straight_from_the_frame"]["overall"]["total"] > 0


def test_eval_perception_measures_the_voter_on_the_tabletops_frames(tmp_path, capsys):
    assert perception_eval.main(["--frames", "12", "--conditions", "tabletop", "--cache", str(tmp_path), "--json"]) == 0
    tabletop = json.loads(capsys.readouterr().out)["tabletop"]
    assert tabletop["frames"] == 12 and tabletop["poses"]["blocks"] > 0
    assert "literals_straight_from_the_frame" not in tabletop
    assert list(tmp_path.glob("tabletop-frames-seed9700000-n12-*.npz"))
