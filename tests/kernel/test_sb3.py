"""The SB3 VecEnv over the batched engine, and the batched scripted opponents."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.vec_env import VecCheckNan, VecMonitor  # noqa: E402

import vooga_env  # noqa: E402
from vooga_env.envs.sb3 import FightVecEnv  # noqa: E402
from vooga_env.kernel import VectorFight  # noqa: E402
from vooga_env.policies import make_policy  # noqa: E402
from vooga_env.policies.batched import NAMES, scripted_actions  # noqa: E402


@pytest.fixture
def one_torch_thread():
    """PPO on a busy 2-core machine: more torch threads only fight over the cores."""
    import torch

    threads = torch.get_num_threads()
    torch.set_num_threads(1)
    yield
    torch.set_num_threads(threads)


def test_self_play_has_two_slots_per_fight_and_sb3_conventions():
    env = FightVecEnv(3, max_cycles=20)
    assert env.num_envs == 6
    assert env.seed(4) == [4, 4, 5, 5, 6, 6]
    observations = env.reset()  # observations only, as SB3 wants
    assert observations.shape == (6, 41) and observations.dtype == np.float32
    # slot 2i and 2i + 1 are fight i's fighters, each seeded like a single env with 4 + i
    single, _ = vooga_env.parallel_env(max_cycles=20).reset(seed=5)
    assert np.array_equal(observations[2], single["fighter_0"])
    assert np.array_equal(observations[3], single["fighter_1"])
    ends = 0
    for _ in range(45):
        observations, rewards, dones, infos = env.step(np.full(6, 2))  # both walk forward
        assert rewards.shape == (6,) and dones.shape == (6,) and len(infos) == 6
        assert np.allclose(rewards[0::2], -rewards[1::2])  # zero-sum
        for slot in np.flatnonzero(dones):
            info = infos[slot]
            assert info["terminal_observation"].shape == (41,)
            assert info["TimeLimit.truncated"] is True  # nobody falls walking into each other
            assert info["winner"] in ("win", "loss", "draw")
            assert observations[slot][-1] == 1.0  # a fresh episode: all its time left
            ends += 1
        assert all(dones[0::2] == dones[1::2])  # both seats of a fight end together
    assert ends == 2 * 3 * 2  # every fight truncated at steps 20 and 40


def test_same_seed_same_rollout_and_the_slots_are_the_batched_engines():
    def rollout():
        env = FightVecEnv(4, opponent="rush", opponent_seed=1, max_cycles=30)
        env.seed(9)
        trace = [env.reset()]
        rng = np.random.default_rng(0)
        for _ in range(40):
            trace.append(env.step(rng.integers(10, size=4))[0])
        return np.stack(trace)

    assert np.array_equal(rollout(), rollout())
    env = FightVecEnv(2, opponent="idle", seat=1)
    env.seed(3)
    fights = VectorFight(2)
    assert np.array_equal(env.reset(), fights.reset(seed=3)[:, 1])


@pytest.mark.parametrize("name", ["random", "rush"])
def test_seed_alone_replays_a_named_opponent_that_draws_random_numbers(name):
    """SB3 seeds a VecEnv with `seed()` only: the opponent's draws must follow it too."""

    def rollout(seed):
        env = FightVecEnv(4, opponent=name, max_cycles=60)
        env.seed(seed)
        trace = [env.reset()]
        for _ in range(80):
            trace.append(env.step(np.zeros(4, dtype=np.int64))[0])
        return np.stack(trace)

    assert np.array_equal(rollout(5), rollout(5))
    assert not np.array_equal(rollout(5)[:, :, 19:], rollout(6)[:, :, 19:])


def test_alternate_seats_put_fight_i_learner_in_seat_i_mod_2():
    env = FightVecEnv(4, opponent="idle", seat="alternate", max_cycles=20, info_events=True)
    env.seed(5)
    seen = env.reset()
    fights = VectorFight(4, max_cycles=20)
    both = fights.reset(seed=5)
    assert np.array_equal(seen, both[[0, 1, 2, 3], [0, 1, 0, 1]])
    rng = np.random.default_rng(2)
    for _ in range(25):  # the learner kicks, idle stands: rewards and outcomes are the learner's
        actions = rng.integers(10, size=4)
        pairs = np.zeros((4, 2), dtype=np.int64)
        pairs[[0, 1, 2, 3], [0, 1, 0, 1]] = actions
        observations, rewards, _, _, info = fights.step(pairs)
        mine, got, dones, infos = env.step(actions)
        assert np.array_equal(mine, observations[[0, 1, 2, 3], [0, 1, 0, 1]])
        assert np.allclose(got, rewards[[0, 1, 2, 3], [0, 1, 0, 1]])
        for slot in np.flatnonzero(dones):
            winner, seat = int(info["winner"][slot]), slot % 2
            expected = "draw" if winner < 0 else ("win" if winner == seat else "loss")
            assert infos[slot]["winner"] == expected
    with pytest.raises(ValueError, match="0, 1 or 'alternate'"):
        FightVecEnv(2, opponent="idle", seat=2)


def test_events_in_infos_on_request():
    env = FightVecEnv(2, opponent="rush", info_events=True)
    env.reset()
    _, _, _, infos = env.step(np.zeros(2, dtype=int))
    assert set(infos[0]) >= {"damage_dealt", "hits_landed", "rung_out", "knocked_out"}


@pytest.mark.parametrize("opponent", [None, "turtle"])
def test_ppo_learns_through_it_without_nans(opponent, one_torch_thread):
    env = VecMonitor(
        VecCheckNan(FightVecEnv(4, opponent=opponent, max_cycles=50), raise_exception=True)
    )
    env.seed(0)
    model = PPO("MlpPolicy", env, n_steps=32, batch_size=64, n_epochs=1, seed=0, device="cpu")
    model.learn(total_timesteps=3 * env.num_envs * 32)
    assert model.num_timesteps >= 3 * env.num_envs * 32
    assert len(model.ep_info_buffer) > 0  # episodes ended and were counted


def observations_from_games(count: int = 1000) -> np.ndarray:
    """Real observations, from both seats of scripted games with random actions mixed in: half
    from rush against zoner, half from an aerial fighter against an edge grappler (in the air,
    cornered)."""
    return np.concatenate(
        [
            scripted_game_observations(("rush", "zoner"), count // 2),
            scripted_game_observations(("aerial", "edge_grappler"), count - count // 2),
        ]
    )


def scripted_game_observations(names: tuple[str, str], count: int) -> np.ndarray:
    env = vooga_env.parallel_env(config="small", max_cycles=100)
    rng = np.random.default_rng(1)
    policies = [make_policy(names[0], 1), make_policy(names[1], 2)]
    obs, _ = env.reset(seed=0)
    rows = []
    while len(rows) < count:
        rows += [obs["fighter_0"], obs["fighter_1"]]
        actions = {
            agent: (int(rng.integers(10)) if rng.random() < 0.3 else policy.act(obs[agent]))
            for agent, policy in zip(env.possible_agents, policies)
        }
        obs, *_ = env.step(actions)
        if not env.agents:
            obs, _ = env.reset()
    return np.stack(rows)


class FixedDraw:
    """Stands in for a scripted policy's generator: `random()` returns the given draw."""

    def __init__(self, draw: float) -> None:
        self.draw = draw

    def random(self) -> float:
        return self.draw


@pytest.mark.parametrize("name", [name for name in NAMES if name != "random"])
def test_batched_scripted_fighters_choose_what_the_single_ones_choose(name):
    observations = observations_from_games()
    draws = np.random.default_rng(2).random(len(observations))
    batched = scripted_actions(name, observations, draws)
    policy = make_policy(name, 0)
    for row, draw, action in zip(observations, draws, batched):
        policy.rng = FixedDraw(float(draw))
        assert policy.act(row) == action


def test_batched_random_fighter_covers_the_actions():
    actions = scripted_actions(
        "random", np.zeros((5000, 41), np.float32), np.linspace(0, 1, 5000, endpoint=False)
    )
    assert set(actions.tolist()) == set(range(10))


def test_episode_infos_are_monitors_and_ppo_logs_them(one_torch_thread):
    env = FightVecEnv(4, opponent="random", opponent_seed=0, max_cycles=25)
    env.seed(3)
    env.reset()
    returns, lengths, seen = np.zeros(4), np.zeros(4, dtype=int), 0
    rng = np.random.default_rng(0)
    for _ in range(60):
        _, rewards, dones, infos = env.step(rng.integers(0, 10, 4))
        returns += rewards
        lengths += 1
        for slot in np.flatnonzero(dones):
            episode = infos[slot]["episode"]
            assert episode["l"] == lengths[slot]
            assert episode["r"] == pytest.approx(returns[slot], abs=1e-4)
            assert episode["t"] >= 0.0
            returns[slot], lengths[slot], seen = 0.0, 0, seen + 1
        assert all("episode" not in infos[s] for s in np.flatnonzero(~dones))
    assert seen >= 8  # every fight ended at least twice (truncation at 25)
    model = PPO("MlpPolicy", FightVecEnv(4, max_cycles=16), n_steps=32, batch_size=64, seed=0)
    model.learn(256)
    assert len(model.ep_info_buffer) > 0  # SB3 found the episodes without a Monitor


def test_env_method_set_opponent_swaps_the_batch_opponent():
    env = FightVecEnv(3, opponent="idle")
    assert env.env_method("set_opponent", "turtle", seed=1) == [None, None, None]
    assert [o.name for o in env.get_attr("opponent")] == ["turtle"] * 3
    with pytest.raises(ValueError, match="unknown scripted fighter 'nobody'"):
        env.env_method("set_opponent", "nobody")
    with pytest.raises(ValueError, match="self-play"):
        FightVecEnv(2).set_opponent("rush")


def test_render_draws_fight_zero_as_the_engine_shows_it():
    env = FightVecEnv(3, render_mode="rgb_array", max_cycles=15)  # self-play: both actions ours
    env.seed(7)
    env.reset()
    single = vooga_env.parallel_env(render_mode="rgb_array", max_cycles=15)
    single.reset(seed=7)  # fight 0 of the batch; it auto-resets, the single env is reset by hand
    actions = np.random.default_rng(1).integers(0, 10, (40, 6))
    for step, slots in enumerate(actions):
        frame = env.render()
        assert frame.shape == (480, 800, 3) and frame.dtype == np.uint8
        assert np.array_equal(frame, single.render()), f"step {step}"
        env.step(slots)
        single.step({"fighter_0": int(slots[0]), "fighter_1": int(slots[1])})
        if not single.agents:
            single.reset()


def test_vec_video_recorder_writes_a_video(tmp_path):
    pytest.importorskip("moviepy")
    from stable_baselines3.common.vec_env import VecVideoRecorder

    env = FightVecEnv(2, opponent="rush", render_mode="rgb_array", max_cycles=10)
    recorder = VecVideoRecorder(env, str(tmp_path), lambda step: step == 0, video_length=12)
    recorder.reset()
    for _ in range(14):
        recorder.step(np.zeros(2, dtype=int))
    recorder.close()
    videos = list(tmp_path.glob("*.mp4"))
    assert videos and videos[0].stat().st_size > 1000


def test_the_batch_refuses_a_render_mode_it_cannot_draw():
    with pytest.raises(ValueError, match="render_mode must be None or 'rgb_array', got 'human'"):
        FightVecEnv(2, render_mode="human")
