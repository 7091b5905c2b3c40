"""`./semgoal eval perception` at a tiny size: the shipped voter and the paper's literal network both load and are
measured on the same held-out frames (the literal network had stopped loading once the tabletop's literals came)."""

import json

from semgoal_bringup.experiments import perception_eval


def test_eval_perception_measures_the_voter_and_the_literal_network_on_a_few_frames(tmp_path, capsys):
    assert perception_eval.main(["--frames", "6", "--conditions", "nominal", "--cache", str(tmp_path), "--json"]) == 0
    nominal = json.loads(capsys.readouterr().out)["nominal"]
    assert nominal["frames"] == 6 and nominal["poses"]["blocks"] > 0
    assert nominal["literals"]["overall"]["total"] > 0
    assert nominal["literals_straight_from_the_frame"]["overall"]["total"] > 0
