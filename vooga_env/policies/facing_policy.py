"""`FacingPolicy`: SB3's MlpPolicy playing in the opponent-facing frame (`game.facing`).

It takes the seat's observations as every env gives them, turns each to face the opponent before
its networks see it, and turns the action distribution back, so `predict`, training and a saved
model all play as they were trained, from either side. `FrozenPolicy` reads its `frame`. Needs
torch and stable-baselines3 (the `train` extra); a saved model of it loads with `load_model`.
"""

from __future__ import annotations

from typing import Any

import torch
from stable_baselines3.common.distributions import Distribution
from stable_baselines3.common.policies import ActorCriticPolicy

from vooga_env.game.facing import MIRROR_INDEX, MIRROR_SIGN, OPPONENT_X, TURNED_ACTIONS


class FacingPolicy(ActorCriticPolicy):
    """An actor-critic MLP whose every input faces the opponent and whose actions turn back."""

    frame = "opponent"

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        if not self.share_features_extractor:
            raise ValueError("FacingPolicy needs share_features_extractor=True")
        self.register_buffer("mirror_index", torch.as_tensor(MIRROR_INDEX), persistent=False)
        self.register_buffer("mirror_sign", torch.as_tensor(MIRROR_SIGN), persistent=False)
        self.register_buffer("turned_actions", torch.as_tensor(TURNED_ACTIONS), persistent=False)
        # rows of a training batch that take the mode instead of a sample (set by the league)
        self.argmax_rows: torch.Tensor | None = None

    def _latent(self, obs: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        """The actor's and critic's latents of the turned observations, and which were turned."""
        turned = obs[:, OPPONENT_X] < 0
        faced = torch.where(turned[:, None], obs[:, self.mirror_index] * self.mirror_sign, obs)
        latent_pi, latent_vf = self.mlp_extractor(self.extract_features(faced))
        return latent_pi, latent_vf, turned

    def _turned_back(self, latent_pi: torch.Tensor, turned: torch.Tensor) -> Distribution:
        logits = self.action_net(latent_pi)
        logits = torch.where(turned[:, None], logits[:, self.turned_actions], logits)
        return self.action_dist.proba_distribution(action_logits=logits)

    def forward(
        self, obs: torch.Tensor, deterministic: bool = False
    ) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        latent_pi, latent_vf, turned = self._latent(obs)
        distribution = self._turned_back(latent_pi, turned)
        actions = distribution.get_actions(deterministic=deterministic)
        if self.argmax_rows is not None and not deterministic:
            actions = torch.where(self.argmax_rows, distribution.mode(), actions)
        return actions, self.value_net(latent_vf), distribution.log_prob(actions)

    def evaluate_actions(
        self, obs: torch.Tensor, actions: torch.Tensor
    ) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        latent_pi, latent_vf, turned = self._latent(obs)
        distribution = self._turned_back(latent_pi, turned)
        return self.value_net(latent_vf), distribution.log_prob(actions), distribution.entropy()

    def get_distribution(self, obs: torch.Tensor) -> Distribution:
        latent_pi, _, turned = self._latent(obs)
        return self._turned_back(latent_pi, turned)

    def predict_values(self, obs: torch.Tensor) -> torch.Tensor:
        return self.value_net(self._latent(obs)[1])


def mlp_policy(frame: str) -> Any:
    """SB3's policy for a learner on vector observations: MlpPolicy by seat, else FacingPolicy."""
    return FacingPolicy if frame == "opponent" else "MlpPolicy"
