"""The semantic state from estimated block positions, with a confidence per literal: the truth values are
``semgoal_core``'s predicates on the estimates (the same functions the simulator's predicate node uses),
and a literal's confidence is the share of position samples, drawn from each block's uncertainty, that
agree with that value. A block never seen gives its literals confidence 0."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from semgoal_core.geometry import TABLE_TOP
from semgoal_core.vocabulary import SemanticLayout, evaluate

SAMPLES = 48
"""Position samples per frame for the confidences (fixed draws: the same estimate gives the same confidence)."""


class SemanticEstimator:
    """Truth values and confidences of one scene's literals."""

    def __init__(self, layout: SemanticLayout, samples: int = SAMPLES, seed: int = 0) -> None:
        self.layout = layout
        self.noise = np.random.default_rng(seed).standard_normal((samples, len(layout.objects), 3))
        index = {name: i for i, name in enumerate(layout.objects)}
        self.atom_blocks = [[index[arg] for arg in args] for _, args in layout.atoms]

    def estimate(self, positions: np.ndarray, sigmas: np.ndarray, grip: np.ndarray, opening: float,
                 present: np.ndarray, other_hands: Sequence[tuple[np.ndarray, float]] = ()
                 ) -> tuple[np.ndarray, np.ndarray]:
        """(vector, confidence): bool and float in [0, 1] per grounded predicate, in the layout's order.

        :param positions: (N, 3) estimated centres in the scene's object order (NaN: never seen).
        :param sigmas: (N, 3) their standard deviations (m).
        :param other_hands: the other arms' grip sites and openings: ``holding`` is in any hand.
        """
        known = np.isfinite(positions).all(axis=1)
        centres = np.where(known[:, None], positions, 0.0)
        vector = evaluate(self.layout, centres, grip, opening, TABLE_TOP, present, other_hands=other_hands)
        agree = np.zeros(self.layout.size)
        for noise in self.noise:
            sample = evaluate(self.layout, centres + noise * sigmas, grip, opening, TABLE_TOP, present,
                              other_hands=other_hands)
            agree += sample == vector
        confidence = agree / len(self.noise)
        unknown = ~known
        for entry, blocks in enumerate(self.atom_blocks):
            if unknown[blocks].any():
                confidence[entry] = 0.0
        return vector & ~np.array([unknown[b].any() for b in self.atom_blocks]), confidence
