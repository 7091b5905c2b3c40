"""The object-centric actor: one set of weights for any scene and any number of blocks.

It takes the same flat observation and goal as :class:`~semgoal_policy.actor.Actor` (so training, HER relabelling
and the controller are unchanged) and reads them as a set of blocks. Every sub-goal's literals name the block it
moves in exactly one ``holding`` literal (:meth:`semgoal_core.vocabulary.SubGoal.literals`), so the goal's mask says
which block that is, also after HER relabels it. Each block becomes a token: its observation slot (present,
position, position relative to the grip, velocity), whether it is the moved block, its offset from the moved block,
and the goal's target and mask of its relations with the moved block (``close``, ``above`` either way) and of its own
(``in_bin``, ``holding``); a scene without a predicate leaves those zero. A shared encoder embeds each token with the
arm's state (and any derived features), a masked mean and max pool the present ones (deep sets: Zaheer et al. 2017),
and a head reads the pools, the moved block's own embedding and the arm. The pools make the output independent of
the order and the number of the other blocks; the weights do not depend on the scene's layout, so an actor trained
on one scene loads for any (``tests/unit/policy/test_object_actor.py``).
"""

from __future__ import annotations

import numpy as np
import torch
from torch import nn

from semgoal_core import layout
from semgoal_core.vocabulary import LAYOUTS
from semgoal_policy.actor import LOG_STD_MAX, LOG_STD_MIN, OBS_CLIP, GaussianPolicy, Normaliser, mlp

ARCHITECTURE = "object"
TOKEN_VERSION = 1
"""Bumped whenever a token's features change: an exported object actor records it and loads only when it matches."""
RELATIONS = (("close", "subject-block"), ("above", "subject-block"), ("above", "block-subject"),
             ("in_bin", "block"), ("holding", "block"))
"""Each token's goal features: target and mask of these atoms, for the token's block and the moved block."""
OFFSET_SCALE = 10.0
"""The offset from the moved block (m) times this: a few tenths, as normalised features are."""
TOKEN_SIZE = layout.BLOCK_SIZE + 1 + 3 + 2 * len(RELATIONS)
EMBEDDING = 128
HEAD = (256, 256)


def relation_indices(scene: str) -> np.ndarray:
    """(R, N, N) int: entry ``[r, s, b]`` is the goal entry of relation ``r`` between the moved block ``s`` and block
    ``b`` in ``scene``'s semantic layout, or the layout's size (a padding entry, always 0) where there is none."""
    semantic = LAYOUTS[scene]
    objects, missing = semantic.objects, semantic.size
    table = np.full((len(RELATIONS), len(objects), len(objects)), missing, dtype=np.int64)
    for r, (name, pattern) in enumerate(RELATIONS):
        for s, subject in enumerate(objects):
            for b, block in enumerate(objects):
                args = {"subject-block": (subject, block), "block-subject": (block, subject), "block": (block,)}[pattern]
                if len(set(args)) < len(args):
                    continue
                atom = semantic.canonical(name, args)
                if atom in semantic.atoms:
                    table[r, s, b] = semantic.index_of_atom(atom)
    return table


class ObjectActor(GaussianPolicy):
    """Squashed Gaussian policy over a set of block tokens (module doc); the interface of ``Actor``."""

    def __init__(self, scene: str, derived_size: int = 0, log_std_max: float = LOG_STD_MAX) -> None:
        super().__init__()
        self.scene, self.derived_size, self.log_std_max = scene, derived_size, log_std_max
        self.blocks = len(LAYOUTS[scene].objects)
        self.obs_size = layout.observation_size(scene) + derived_size
        self.goal_size = 2 * LAYOUTS[scene].size
        context = layout.ARM_SIZE + derived_size
        self.normaliser = TokenNormaliser(scene, derived_size)
        self.net = nn.ModuleDict({"token": mlp(TOKEN_SIZE + context, EMBEDDING, (EMBEDDING,)),
                                  "head": mlp(context + 3 * EMBEDDING, 8, HEAD)})
        self.register_buffer("relations", torch.as_tensor(relation_indices(scene)), persistent=False)
        holding = [LAYOUTS[scene].index_of_atom(("holding", (block,))) for block in LAYOUTS[scene].objects]
        self.register_buffer("holding_entries", torch.as_tensor(holding), persistent=False)

    @property
    def feature_size(self) -> int:
        """Width of :meth:`features`, the critic's input."""
        return self.blocks * TOKEN_SIZE + layout.ARM_SIZE + self.derived_size

    def tokens(self, obs: torch.Tensor, goal: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor, torch.Tensor]:
        """(tokens (B, N, TOKEN_SIZE), context (B, C), present (B, N) bool, subject (B,) long) of a batch."""
        arm, blocks, derived = self.normaliser(obs)
        raw = obs[:, layout.ARM_SIZE:layout.ARM_SIZE + self.blocks * layout.BLOCK_SIZE].reshape(-1, self.blocks, layout.BLOCK_SIZE)
        present = raw[..., 0] > 0.5
        size = self.goal_size // 2
        target, mask = goal[:, :size], goal[:, size:]
        subject = mask[:, self.holding_entries].argmax(dim=1)
        rows = torch.arange(len(obs))
        is_subject = torch.zeros_like(present, dtype=obs.dtype)
        is_subject[rows, subject] = 1.0
        position = raw[..., 1:4]
        offset = (position - position[rows, subject].unsqueeze(1)) * OFFSET_SCALE * present.unsqueeze(-1)
        pad = torch.zeros(len(obs), 1, dtype=goal.dtype)
        entries = self.relations[:, subject].permute(1, 2, 0)  # (B, N, R)
        flat = entries.reshape(len(obs), -1)
        goal_target = torch.cat([target, pad], 1).gather(1, flat).reshape(entries.shape)
        goal_mask = torch.cat([mask, pad], 1).gather(1, flat).reshape(entries.shape)
        tokens = torch.cat([blocks, is_subject.unsqueeze(-1), offset, goal_target, goal_mask], dim=-1)
        tokens = tokens * present.unsqueeze(-1)
        context = torch.cat([arm, derived], dim=-1)
        return tokens, context, present, subject

    def features(self, obs: torch.Tensor, goal: torch.Tensor) -> torch.Tensor:
        """The tokens and the context as one flat vector per row (a scene's critic reads it)."""
        tokens, context, _, _ = self.tokens(obs, goal)
        return torch.cat([tokens.flatten(1), context], dim=-1)

    def forward(self, obs: torch.Tensor, goal: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """(mean, log_std) of the pre-tanh Gaussian, for a batch or one row (as the controller acts)."""
        if obs.dim() == 1:
            mean, log_std = self.forward(obs.unsqueeze(0), goal.unsqueeze(0))
            return mean[0], log_std[0]
        tokens, context, present, subject = self.tokens(obs, goal)
        expanded = context.unsqueeze(1).expand(-1, tokens.shape[1], -1)
        embedded = self.net["token"](torch.cat([tokens, expanded], dim=-1))
        weight = present.unsqueeze(-1).to(embedded.dtype)
        mean_pool = (embedded * weight).sum(1) / weight.sum(1).clamp(min=1.0)
        max_pool = embedded.masked_fill(~present.unsqueeze(-1), -1e9).max(1).values
        own = embedded[torch.arange(len(obs)), subject]
        head = self.net["head"](torch.cat([context, mean_pool, max_pool, own], dim=-1)).float()  # fp32 under autocast
        mean, log_std = head.chunk(2, dim=-1)
        return mean, torch.clamp(log_std, LOG_STD_MIN, self.log_std_max)


class TokenNormaliser(nn.Module):
    """Running statistics of the arm's features, of a block slot's (shared by every present block) and of the
    derived features: the same for every scene and number of blocks."""

    def __init__(self, scene: str, derived_size: int) -> None:
        super().__init__()
        self.blocks, self.derived_size = len(LAYOUTS[scene].objects), derived_size
        self.arm = Normaliser(layout.ARM_SIZE)
        self.block = Normaliser(layout.BLOCK_SIZE)
        self.derived = Normaliser(max(derived_size, 1))

    def _split(self, obs: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        end = layout.ARM_SIZE + self.blocks * layout.BLOCK_SIZE
        blocks = obs[:, layout.ARM_SIZE:end].reshape(len(obs), self.blocks, layout.BLOCK_SIZE)
        return obs[:, :layout.ARM_SIZE], blocks, obs[:, end:end + self.derived_size]

    def update(self, batch: np.ndarray) -> None:
        arm, blocks, derived = self._split(torch.as_tensor(np.asarray(batch, dtype=np.float64).reshape(len(batch), -1)))
        self.arm.update(arm.numpy())
        self.block.update(blocks[blocks[..., 0] > 0.5].numpy())
        if self.derived_size:
            self.derived.update(derived.numpy())

    def forward(self, obs: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        """(arm, blocks, derived) normalised and clipped to +-:data:`OBS_CLIP` (the blocks' ``present`` kept 0/1)."""
        arm, blocks, derived = self._split(obs)
        normalised = self.block(blocks)
        normalised = torch.cat([blocks[..., :1], normalised[..., 1:]], dim=-1)
        derived = self.derived(derived) if self.derived_size else derived
        return self.arm(arm), normalised, derived.clamp(-OBS_CLIP, OBS_CLIP)
