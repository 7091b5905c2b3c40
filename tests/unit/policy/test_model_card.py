"""Every shipped or pooled actor has its model card, and the card is what its actor.json says today."""

from pathlib import Path

import pytest

from semgoal_policy.model_card import model_card, steps_to_reach

MODELS = Path(__file__).parents[3] / "src" / "semgoal_policy" / "models"
ACTORS = sorted(path.parent for path in MODELS.rglob("actor.json"))


@pytest.mark.parametrize("directory", ACTORS, ids=lambda d: d.relative_to(MODELS).as_posix())
def test_the_card_is_current(directory: Path) -> None:
    card = directory / "MODEL_CARD.md"
    assert card.exists(), f"no card: ./semgoal model-card {directory}"
    assert card.read_text() == model_card(directory), f"stale card: ./semgoal model-card {directory}"


def test_there_are_actors_to_check() -> None:
    assert len(ACTORS) >= 9


def test_steps_to_reach_count_a_rate_held_over_three_evaluations_not_one_lucky_one() -> None:
    rates = {"pick": [0.5, 0.95, 0.6, 0.9, 0.9, 0.95], "put_on": [0.2, 0.3, 0.95, 0.4, 0.5, 0.6]}
    rows = [{"env_steps": str(10_000 * (i + 1)), "eval/success/overall": "0", **{f"eval/success/{k}": str(v[i])
             for k, v in rates.items()}} for i in range(6)]
    assert steps_to_reach(rows) == {"pick": 60_000, "put_on": None}
    assert steps_to_reach(rows, window=1) == {"pick": 20_000, "put_on": 30_000}


def test_steps_to_reach_a_kind_reported_from_later_on_counts_its_own_evaluations() -> None:
    rates = {"pick": ["0.95"] * 5, "take_out": ["", "", "0.9", "0.9", "0.95"]}
    rows = [{"env_steps": str(10_000 * (i + 1)), "eval/success/overall": "0", **{f"eval/success/{k}": v[i]
             for k, v in rates.items()}} for i in range(5)]
    assert steps_to_reach(rows) == {"pick": 30_000, "take_out": 50_000}
