"""Every shipped or pooled actor has its model card, and the card is what its actor.json says today."""

from pathlib import Path

import pytest

from semgoal_policy.model_card import model_card

MODELS = Path(__file__).parents[3] / "src" / "semgoal_policy" / "models"
ACTORS = sorted(path.parent for path in MODELS.rglob("actor.json"))


@pytest.mark.parametrize("directory", ACTORS, ids=lambda d: d.relative_to(MODELS).as_posix())
def test_the_card_is_current(directory: Path) -> None:
    card = directory / "MODEL_CARD.md"
    assert card.exists(), f"no card: ./semgoal model-card {directory}"
    assert card.read_text() == model_card(directory), f"stale card: ./semgoal model-card {directory}"


def test_there_are_actors_to_check() -> None:
    assert len(ACTORS) >= 9
