"""The paper's alternative: its targets are the scene's predicates on the labelled centres, its outputs one
probability per literal of every scene."""

from types import SimpleNamespace

import numpy as np
import torch

from semgoal_core.tasks import get_task
from semgoal_perception.literal_net import ATOMS, INDEX, LiteralNet, targets


def test_targets_are_the_scenes_literals_on_the_true_centres_and_mask_the_rest() -> None:
    centres = np.full((1, 4, 3), np.nan)
    centres[0, 0], centres[0, 1] = [1.3, 0.7, 0.475], [1.3, 0.7, 0.425]  # red on green
    frames = SimpleNamespace(rgb=np.zeros((1, 2, 2, 3)), centres=centres, grip=np.array([[1.3, 0.5, 0.6, 0.1]]))
    truth, mask = targets(frames, [get_task("Swap-2")])
    assert truth[0, INDEX[("above", ("red", "green"))]] == 1.0 and truth[0, INDEX[("above", ("green", "red"))]] == 0.0
    assert mask[0].sum() == 5  # two_blocks: close, above both ways, holding each
    assert mask[0, INDEX[("in_bin", ("red",))]] == 0.0


def test_the_network_gives_one_logit_per_literal() -> None:
    net = LiteralNet().eval()
    with torch.inference_mode():
        assert net(torch.zeros(2, 7, 120, 160), torch.zeros(2, 4)).shape == (2, len(ATOMS))
