"""The curriculum's opponents: mixed rungs, review of earlier rungs, a draw for every game."""

from collections import Counter

import pytest

pytest.importorskip("stable_baselines3")

from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.callbacks import BaseCallback  # noqa: E402
from stable_baselines3.common.env_util import make_vec_env  # noqa: E402
from stable_baselines3.common.vec_env import DummyVecEnv  # noqa: E402

from agents.callbacks import CurriculumCallback  # noqa: E402
from agents.train_config import CurriculumConfig  # noqa: E402
from vooga_env.envs.gym_env import FightEnv  # noqa: E402
from vooga_env.game.config import ConfigError  # noqa: E402


class Opponents(BaseCallback):
    """Counts the opponent of every finished game, per env."""

    def __init__(self, envs: int) -> None:
        super().__init__()
        self.seen = [Counter() for _ in range(envs)]

    def _on_step(self) -> bool:
        for index, (done, info) in enumerate(zip(self.locals["dones"], self.locals["infos"])):
            if done:
                self.seen[index][info["opponent"]] += 1
        return True


def games(config: CurriculumConfig, envs: int = 2, steps: int = 1024) -> list[Counter]:
    vec = make_vec_env(
        FightEnv,
        n_envs=envs,
        seed=0,
        vec_env_cls=DummyVecEnv,
        env_kwargs={"config": "small", "opponent": "random", "seat": "random", "max_cycles": 16},
    )
    model = PPO("MlpPolicy", vec, n_steps=128, batch_size=128, n_epochs=1, seed=0, device="cpu")
    opponents = Opponents(envs)
    model.learn(steps, callback=[CurriculumCallback(config, seed=0), opponents])
    return opponents.seen


def test_a_mixed_rung_draws_each_of_its_fighters_game_by_game():
    seen = games(CurriculumConfig(ladder=("idle+rush+turtle",), window=10_000, review_ratio=0.0))
    for counts in seen:
        assert set(counts) == {"idle", "rush", "turtle"}, counts


def test_reviewers_replay_earlier_rungs_and_the_others_stay_on_the_current_one():
    # idle's games are all draws or wins for the learner: promoted past it at once
    config = CurriculumConfig(ladder=("idle", "zoner"), promote_win_rate=0.01, window=1)
    seen = games(config, envs=4)
    assert seen[0]["idle"] <= 2 and seen[0]["zoner"] > 10  # idle till promoted, then zoner only
    assert seen[3]["idle"] > 1 and seen[3]["zoner"] > 1  # the reviewer draws both rungs


def test_a_mixed_rung_with_a_typo_names_the_fighter():
    with pytest.raises(ConfigError, match="'ninja' is not one of idle"):
        CurriculumConfig(ladder=("rush+ninja",))
