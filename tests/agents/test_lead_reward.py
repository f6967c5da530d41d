"""The reward for leading: who leads is who a win on time pays, and the wrapper adds it per slot."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import vooga_env
from agents.lead_reward import LeadReward, leads
from agents.league import build, load_league_config
from vooga_env.envs.sb3 import FightVecEnv
from vooga_env.game.config import load_config
from vooga_env.game.observations import observe_both


@settings(max_examples=100, deadline=None)
@given(st.integers(0, 3), st.integers(0, 3), st.integers(1, 100), st.integers(1, 100))
def test_the_leader_is_the_fighter_a_win_on_time_pays(stocks_0, stocks_1, health_0, health_1):
    env = vooga_env.parallel_env(backend="engine", stocks=3)
    env.reset(seed=0)
    fight = env.fight
    for fighter, stocks, health in zip(fight.fighters, (stocks_0, stocks_1), (health_0, health_1)):
        fighter.stocks, fighter.health = stocks, float(health)
    winner = fight.winner()
    expected = [0, 0] if winner is None else [1 if winner == 0 else -1, 1 if winner == 1 else -1]
    assert leads(observe_both(fight)).tolist() == expected


def test_each_slot_gains_per_step_while_it_leads_and_loses_it_while_it_trails():
    def fights():
        return FightVecEnv(8, load_config("default"), opponent="rush", seat="alternate",
                           opponent_seed=0)  # fmt: skip

    plain, shaped = fights(), LeadReward(fights(), per_step=0.01)
    plain.seed(3)
    shaped.seed(3)
    assert np.array_equal(plain.reset(), shaped.reset())
    rng = np.random.default_rng(0)
    seen = set()
    for _ in range(300):
        actions = rng.integers(0, plain.action_space.n, size=8)
        observations, rewards, _, _ = plain.step(actions)
        shaped_observations, shaped_rewards, _, _ = shaped.step(actions)
        assert np.array_equal(observations, shaped_observations)
        lead = leads(observations)
        np.testing.assert_allclose(shaped_rewards - rewards, 0.01 * lead, atol=1e-6)
        seen.update(lead.tolist())
    assert seen == {-1.0, 0.0, 1.0}


def test_the_league_pays_it_only_when_asked(tmp_path):
    def shaping(config, folder):
        env = build(config, folder, {}, resume=False, saved=None)[0].get_env()
        while not isinstance(env, (LeadReward, FightVecEnv)):
            env = env.venv  # VecNormalize, where the config asks for it
        return env

    on = shaping(load_league_config("smoke"), tmp_path / "on")  # lead_reward = 0.005
    assert isinstance(on, LeadReward) and on.per_step == 0.005
    off = load_league_config("smoke", league={"lead_reward": 0.0})
    assert isinstance(shaping(off, tmp_path / "off"), FightVecEnv)
