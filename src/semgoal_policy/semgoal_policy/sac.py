"""Soft actor-critic for goal-conditioned control with a Q-filtered behaviour-cloning term.

Reads top to bottom like the maths: twin critics with Polyak targets, a tanh-Gaussian actor, automatic
entropy tuning (Haarnoja et al. 2018). Expert supervision (paper, "Training the low-level policy"):
the actor also imitates the scripted expert's action where the critic rates it higher than its own
(the Q-filter of Nair et al. 2018), on a second batch drawn without relabelling, so every sample of it
carries the expert's label for its goal (DAgger-style: labels on the states the agent visited).
"""

from __future__ import annotations

import copy
from dataclasses import dataclass

import numpy as np
import torch
from torch import nn

from semgoal_core import layout
from semgoal_policy.actor import LOG_STD_MAX, Actor, GaussianPolicy, mlp
from semgoal_policy.object_actor import ObjectActor
from semgoal_policy.replay import Batch


@dataclass
class SacConfig:
    gamma: float = 0.98
    """Discount; the HER papers' value for 50-step Fetch episodes."""
    tau: float = 0.005
    """Polyak rate of the target critics."""
    lr: float = 1e-3
    batch_size: int = 256
    bc_weight: float = 1.0
    """Weight of the behaviour-cloning loss; 0 turns expert supervision off in the loss."""
    q_filter: bool = True
    """Clone the expert only where Q(s, a_expert) > Q(s, pi(s))."""
    actor_average_rate: float = 0.0
    """Polyak rate of an averaged copy of the actor, the one evaluated and exported (0: off, the live actor
    is). A few thousand gradient steps can move a desk actor's DC-4 rate by tens of points: an
    average over the last ~1/rate updates smooths that out; the live actor still explores."""
    target_entropy: float = -4.0
    """Entropy the temperature is tuned toward; -4 (minus the action size) is SB3's default. With three
    precise displacement dims the fourth, the fingers, takes up what is left: at -4 the shipped actors'
    finger std sits at its clamp (e^2) in 6-17 % of steps, mostly while a block is held."""
    log_std_max: float = LOG_STD_MAX
    """Upper clamp of the actor's log std. At e^2 the finger's tanh-Gaussian is a coin flip whose mean
    barely moves the samples, so the mean (the deterministic actor) learns little where a block is held:
    it freezes there while the sampled actor lets go by chance (``docs/history.md``)."""
    mean_reg: float = 0.0
    """Weight of an L2 penalty on the actor's pre-tanh mean (rlkit's ``policy_mean_reg_weight``; 0: off). The
    finger labels are exactly -1 or 1, so cloning them drives the mean towards infinity, where tanh's
    gradient vanishes: a quarter to a third of the finger means sit beyond 2.5. The penalty removes that,
    but it did not free three_blocks' put near (it lowered it, ``docs/history.md``), so it stays off:
    the expert's closed-finger labels hold the hand shut there."""
    precision: str = "fp32"
    """``bf16``: the update's matrix products in bfloat16 under ``torch.autocast`` (weights, optimiser state, losses
    and acting stay fp32): about half an update's time on CPUs with AVX512-BF16 or AMX, slower on others
    (``semgoal bench policy`` measures both)."""
    architecture: str = "mlp"
    """``mlp``: the scene's flat actor (:class:`~semgoal_policy.actor.Actor`); ``object``: the object-centric one
    (:class:`~semgoal_policy.object_actor.ObjectActor`), whose weights serve any scene and number of blocks."""


ARCHITECTURES = ("mlp", "object")
PRECISIONS = ("fp32", "bf16")


def bf16_is_native() -> bool:
    """Whether this CPU multiplies bfloat16 matrices in hardware (AVX512-BF16 or AMX), where ``bf16`` pays."""
    return torch.backends.mkldnn.is_available() and torch.ops.mkldnn._is_mkldnn_bf16_supported()


def make_actor(config: SacConfig, obs_size: int, goal_size: int, scene: str = "") -> GaussianPolicy:
    """The actor ``config.architecture`` names, for ``obs_size`` / ``goal_size`` (an object-centric one for ``scene``,
    the derived features being what the observation has past the scene's layout)."""
    if config.architecture == "mlp":
        return Actor(obs_size, goal_size, log_std_max=config.log_std_max)
    if config.architecture == "object":
        return ObjectActor(scene, obs_size - layout.observation_size(scene), log_std_max=config.log_std_max)
    raise ValueError(f"unknown actor architecture {config.architecture!r}; valid: {', '.join(ARCHITECTURES)}")


class TwinCritic(nn.Module):
    def __init__(self, inputs: int) -> None:
        super().__init__()
        self.q1, self.q2 = mlp(inputs + 4, 1), mlp(inputs + 4, 1)

    def forward(self, features: torch.Tensor, action: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        x = torch.cat([features, action], dim=-1)
        return self.q1(x).squeeze(-1).float(), self.q2(x).squeeze(-1).float()  # fp32 under a bf16 autocast too


class SacAgent:
    """Actor, critics, targets, optimisers and the entropy temperature; ``update`` does one gradient step."""

    def __init__(self, obs_size: int, goal_size: int, config: SacConfig, scene: str = "") -> None:
        """``scene``: the scene trained on, which an object-centric actor reads its layout from."""
        if config.precision not in PRECISIONS:
            raise ValueError(f"unknown precision {config.precision!r}; valid: {', '.join(PRECISIONS)}")
        self.config = config
        self.actor = make_actor(config, obs_size, goal_size, scene)
        self.actor_average = None
        if config.actor_average_rate:
            self.actor_average = copy.deepcopy(self.actor).requires_grad_(False)
            self.actor_average.normaliser = self.actor.normaliser  # one set of observation statistics
        self.critic = TwinCritic(self.actor.feature_size)
        self.critic_target = copy.deepcopy(self.critic).requires_grad_(False)
        # the parameters listed once: walking the modules for them every update cost a few per cent of a bf16 update
        self._critic_params, self._target_params = list(self.critic.parameters()), list(self.critic_target.parameters())
        self.log_alpha = torch.zeros(1, requires_grad=True)
        # fused: one kernel per step instead of one per tensor, 5 % off a whole update on a CPU
        self.actor_optimizer = torch.optim.Adam(self.actor.net.parameters(), lr=config.lr, fused=True)
        self.critic_optimizer = torch.optim.Adam(self.critic.parameters(), lr=config.lr, fused=True)
        self.alpha_optimizer = torch.optim.Adam([self.log_alpha], lr=config.lr)
        # values are sums of 0/1 rewards: clip targets to what a discounted sum can reach
        self.q_max = 1.0 / (1.0 - config.gamma)

    def update(self, batch: Batch, bc_batch: Batch | None = None) -> dict[str, float]:
        """One gradient step of critics, actor (SAC + cloning on ``bc_batch``) and temperature."""
        cfg = self.config
        t = {name: torch.as_tensor(value) for name, value in batch._asdict().items()}
        alpha = self.log_alpha.exp().detach()
        with self._autocast():
            features = self.actor.features(t["obs"], t["goal"])
            next_features = self.actor.features(t["next_obs"], t["goal"])
            with torch.no_grad():
                next_action, next_log_pi, _ = self.actor.sample(t["next_obs"], t["goal"])
                qf1_next, qf2_next = self.critic_target(next_features, next_action)
                min_qf_next_target = torch.min(qf1_next, qf2_next) - alpha * next_log_pi
                next_q_value = (t["reward"] + cfg.gamma * min_qf_next_target).clamp(0.0, self.q_max)
            qf1, qf2 = self.critic(features, t["action"])
            critic_loss = ((qf1 - next_q_value) ** 2).mean() + ((qf2 - next_q_value) ** 2).mean()
        self.critic_optimizer.zero_grad()
        critic_loss.backward()
        self.critic_optimizer.step()

        for p in self._critic_params:  # the actor's loss reads the critic, whose weights it must not move
            p.requires_grad_(False)
        with self._autocast():
            obs, goal, size = t["obs"], t["goal"], len(t["obs"])
            bc = None
            if cfg.bc_weight != 0.0 and bc_batch is not None:  # one actor pass over both batches, not two
                bc = {name: torch.as_tensor(value) for name, value in bc_batch._asdict().items()}
                obs, goal = torch.cat([obs, bc["obs"]]), torch.cat([goal, bc["goal"]])
            mean, log_std = self.actor(obs, goal)
            action, log_pi, pre_tanh_mean = self.actor.squashed(mean[:size], log_std[:size])
            min_qf_pi = torch.min(*self.critic(features, action))
            # scale-free SAC term (as TD3+BC does), so the BC weight means the same at every Q magnitude
            q_scale = min_qf_pi.abs().mean().detach().clamp(min=1e-3)
            sac_loss = ((alpha * log_pi - min_qf_pi) / q_scale).mean()
            bc_loss, bc_fraction = (torch.zeros(()), 0.0) if bc is None else self._bc_loss(bc, torch.tanh(mean[size:]))
            actor_loss = sac_loss + cfg.bc_weight * bc_loss + cfg.mean_reg * pre_tanh_mean.pow(2).sum(-1).mean()
        for p in self._critic_params:
            p.requires_grad_(True)
        self.actor_optimizer.zero_grad()
        actor_loss.backward()
        self.actor_optimizer.step()

        alpha_loss = -(self.log_alpha * (log_pi.detach() + cfg.target_entropy)).mean()
        self.alpha_optimizer.zero_grad()
        alpha_loss.backward()
        self.alpha_optimizer.step()

        with torch.no_grad():
            torch._foreach_lerp_(self._target_params, self._critic_params, cfg.tau)
            if self.actor_average is not None:
                for p, p_average in zip(self.actor.net.parameters(), self.actor_average.net.parameters(), strict=True):
                    p_average.lerp_(p, cfg.actor_average_rate)
        return {"train/critic_loss": critic_loss.item(), "train/actor_loss": actor_loss.item(),
                "train/bc_loss": bc_loss.item(), "train/bc_fraction": bc_fraction,
                "train/alpha": alpha.item(), "train/q": min_qf_pi.mean().item()}

    def _autocast(self) -> torch.autocast:
        """The forward passes' precision (:attr:`SacConfig.precision`); backward passes run outside it."""
        return torch.autocast("cpu", dtype=torch.bfloat16, enabled=self.config.precision == "bf16")

    def _bc_loss(self, t: dict[str, torch.Tensor], mean_action: torch.Tensor) -> tuple[torch.Tensor, float]:
        """The cloning loss on batch ``t``, where the actor's mean action is ``mean_action``, and the share of it
        cloned."""
        features = self.actor.features(t["obs"], t["goal"])
        keep = t["has_label"]
        if self.config.q_filter:
            with torch.no_grad():  # the expert's action and the actor's through the critic at once
                q_expert, q_actor = torch.min(*self.critic(features.repeat(2, 1),
                                                           torch.cat([t["expert_action"], mean_action]))).chunk(2)
            keep = keep * (q_expert >= q_actor).float()
        per_sample = ((mean_action - t["expert_action"]) ** 2).sum(-1)
        return (per_sample * keep).sum() / keep.sum().clamp(min=1.0), keep.mean().item()

    @property
    def policy(self) -> GaussianPolicy:
        """The actor to evaluate and export: the averaged one when averaging is on, else the live one."""
        return self.actor if self.actor_average is None else self.actor_average

    # -- checkpoints ---------------------------------------------------------------------------------
    def state_dict(self) -> dict:
        averaged = {} if self.actor_average is None else {"actor_average": self.actor_average.state_dict()}
        return {
            **averaged, "actor": self.actor.state_dict(), "critic": self.critic.state_dict(),
            "critic_target": self.critic_target.state_dict(), "log_alpha": self.log_alpha.detach(),
            "actor_optimizer": self.actor_optimizer.state_dict(),
            "critic_optimizer": self.critic_optimizer.state_dict(),
            "alpha_optimizer": self.alpha_optimizer.state_dict(),
        }

    def load_state_dict(self, state: dict) -> None:
        self.actor.load_state_dict(state["actor"])
        if self.actor_average is not None:  # a checkpoint from before averaging starts it at the actor
            self.actor_average.load_state_dict(state.get("actor_average", state["actor"]))
        self.critic.load_state_dict(state["critic"])
        self.critic_target.load_state_dict(state["critic_target"])
        with torch.no_grad():
            self.log_alpha.copy_(state["log_alpha"])
        self.actor_optimizer.load_state_dict(state["actor_optimizer"])
        self.critic_optimizer.load_state_dict(state["critic_optimizer"])
        self.alpha_optimizer.load_state_dict(state["alpha_optimizer"])
        for optimiser in (self.actor_optimizer, self.critic_optimizer, self.alpha_optimizer):
            fused = optimiser.defaults["fused"]  # a checkpoint from before fused Adam keeps the speed-up
            for group in optimiser.param_groups:  # the configured rate wins: a resumed run may fine-tune slower
                group["lr"], group["fused"] = self.config.lr, fused

    def explore(self, obs: np.ndarray, goal: np.ndarray) -> np.ndarray:
        """Stochastic actions for a batch of envs."""
        with torch.no_grad():
            action, _, _ = self.actor.sample(torch.as_tensor(obs), torch.as_tensor(goal))
        return action.numpy()
