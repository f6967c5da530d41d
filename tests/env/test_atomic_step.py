"""A `Fight.step` (or an env step) that raises leaves the fight as it was before the call."""

from __future__ import annotations

import numpy as np
import pytest

import vooga_env
from vooga_env.game.config import load_config
from vooga_env.game.fight import Fight
from vooga_env.physics import CollisionKind, CollisionKindCustom


class FailsAtFrame(CollisionKind):
    """A kind that raises when asked about a pair in physics frame `frame` of `fight`."""

    def __init__(self, fight: Fight, frame: int) -> None:
        super().__init__()
        self.fight, self.frame = fight, frame

    def is_this_kind(self, sprite_one, sprite_two) -> bool:
        if self.fight.frame == self.frame:
            raise RuntimeError(f"kind failed in frame {self.frame}")
        return False


def fight_state(fight: Fight) -> tuple:
    """Every fighter and hitbox attribute that a step changes, floats as hex (bit for bit)."""
    state = [fight.frame, fight.steps]
    for fighter in fight.fighters:
        for sprite in (fighter, fighter.hitbox):
            for key, value in sorted(vars(sprite).items()):
                if key in ("status", "response", "config", "hitbox", "owner", "serial"):
                    continue
                if isinstance(value, float):
                    value = value.hex()
                elif isinstance(value, set):
                    value = sorted(member.name for member in value)
                state.append((sprite.name, key, value))
    return tuple(state)


def started(seed: int = 3) -> Fight:
    fight = Fight(load_config("default", frame_skip=3, arena={"spawn_jitter": 20.0}))
    fight.reset(np.random.default_rng(seed))
    for action in (5, 2, 7, 3, 8, 1):  # jumping, walking, attacking: mid-air and mid-move
        fight.step((action, 9 - action))
    return fight


@pytest.mark.parametrize("frame", [None, 0, 1, 2], ids=["custom-without-set-type", "0", "1", "2"])
def test_a_failed_fight_step_changes_nothing(frame):
    """Whichever of the step's three physics frames fails, the fight is as before the step."""
    fight, twin = started(), started()
    before = fight_state(fight)
    assert before == fight_state(twin)
    bad_kind = CollisionKindCustom() if frame is None else FailsAtFrame(fight, fight.frame + frame)
    fight.world.collision.add_collision_kind(bad_kind)
    with pytest.raises(RuntimeError):
        fight.step((6, 4))
    assert fight_state(fight) == before
    fight.world.collision.remove_collision_kind(bad_kind)
    for actions in ((6, 4), (2, 7), (0, 0)):
        fight.step(actions)
        twin.step(actions)
        assert fight_state(fight) == fight_state(twin)


def test_a_reward_function_that_fails_undoes_the_step():
    calls = []

    def flaky(fight, events):
        calls.append(fight.steps)
        if len(calls) == 3:
            raise ZeroDivisionError("reward failed")
        return 0.0, 0.0

    env = vooga_env.parallel_env(backend="engine", reward_fn=flaky)
    twin = vooga_env.parallel_env(backend="engine", reward_fn=lambda fight, events: (0.0, 0.0))
    for each in (env, twin):
        each.reset(seed=5)
    actions = {"fighter_0": 5, "fighter_1": 4}
    for _ in range(2):
        env.step(actions), twin.step(actions)
    before = fight_state(env.fight)
    with pytest.raises(ZeroDivisionError):
        env.step(actions)
    assert fight_state(env.fight) == before
    assert (
        env.step(actions)[0]["fighter_0"].tobytes() == twin.step(actions)[0]["fighter_0"].tobytes()
    )
    assert fight_state(env.fight) == fight_state(twin.fight)


@pytest.mark.parametrize("bad", [None, (1.0,), (1.0, 2.0, 3.0), ("a", "b"), (float("nan"), 0.0)])
def test_a_reward_function_returning_no_pair_is_blamed_and_the_step_undone(bad):
    env = vooga_env.parallel_env(backend="engine", reward_fn=lambda fight, events: bad)
    env.reset(seed=0)
    before = fight_state(env.fight)
    with pytest.raises(ValueError, match=r"reward_fn .* two finite numbers"):
        env.step({"fighter_0": 2, "fighter_1": 2})
    assert fight_state(env.fight) == before
