"""Hand-placed fights with results derived from the config's numbers."""

import pytest

import vooga_env
from vooga_env.game.actions import Action

PUNCH, KICK, BLOCK, IDLE = Action.PUNCH, Action.KICK, Action.BLOCK, Action.IDLE


def face_off(gap, **overrides):
    """Both fighters standing on the stage, `gap` px between them, fighter_0 on the left.

    Without the edge shaping, so that rewards are the hits' and ring-outs' alone.
    """
    env = vooga_env.parallel_env(rewards={"edge": 0.0}, backend="engine", **overrides)
    env.reset(seed=0)
    one, two = env.fight.fighters
    two.x = one.right + gap
    return env, one, two


def run(env, actions, steps):
    totals = {agent: 0.0 for agent in env.possible_agents}
    infos = []
    for _ in range(steps):
        if not env.agents:
            break
        _, rewards, _, _, info = env.step(dict(zip(env.possible_agents, actions)))
        infos.append(info)
        for agent in totals:
            totals[agent] += rewards[agent]
    return totals, infos


def test_a_punch_that_connects_deals_its_damage_once():
    env, one, two = face_off(10.0)
    punch = env.config.fighter.punch
    health = env.config.fighter.health
    totals, infos = run(env, (PUNCH, IDLE), 1)
    frames = punch.startup + punch.active + punch.recovery
    totals_after, more = run(env, (IDLE, IDLE), frames)
    infos += more
    assert sum(info["fighter_0"]["hits_landed"] for info in infos) == 1
    assert two.health == health - punch.damage
    weight = env.config.rewards.damage
    assert totals["fighter_0"] + totals_after["fighter_0"] == pytest.approx(
        weight * punch.damage / health
    )
    assert totals["fighter_1"] + totals_after["fighter_1"] == pytest.approx(
        -weight * punch.damage / health
    )


def test_an_attack_out_of_reach_deals_nothing():
    env, one, two = face_off(env_gap := 60.0)
    assert env_gap > env.config.fighter.punch.hitbox_width
    run(env, (PUNCH, IDLE), 10)
    assert two.health == env.config.fighter.health


def test_blocking_cuts_damage_and_knockback():
    results = {}
    for defence in (IDLE, BLOCK):
        env, one, two = face_off(10.0)
        run(env, (IDLE, defence), 1)
        run(env, (KICK, defence), 4)
        results[defence] = (env.config.fighter.health - two.health, abs(two.vx))
    fighter = vooga_env.load_config().fighter
    assert results[IDLE][0] == fighter.kick.damage
    assert results[BLOCK][0] == pytest.approx(fighter.kick.damage * fighter.block_damage)
    assert results[BLOCK][1] < results[IDLE][1]


def test_crouching_ducks_a_punch_but_not_a_kick():
    for attack, lands in ((PUNCH, False), (KICK, True)):
        env, one, two = face_off(10.0)
        run(env, (IDLE, Action.DOWN), 1)
        run(env, (attack, Action.DOWN), 8)
        assert (two.health < env.config.fighter.health) == lands


def test_a_kick_from_a_crouch_stays_low_and_ducks_the_punch_it_beats():
    env, one, two = face_off(10.0)
    run(env, (Action.DOWN, IDLE), 1)
    run(env, (KICK, PUNCH), 1)
    assert one.crouching and one.move == "kick"
    run(env, (IDLE, IDLE), 8)
    fighter = env.config.fighter
    assert one.health == fighter.health
    assert two.health == fighter.health - fighter.kick.damage


def test_a_fighter_knocked_past_the_edge_falls_and_is_rung_out():
    env, one, two = face_off(10.0)
    stage_right = env.fight.stage_right
    one.x = stage_right - 100.0
    two.x = one.right + 10.0
    two.health = 20.0  # damage taken grows the knockback
    totals, infos = run(env, (KICK, IDLE), 200)
    last = infos[-1]
    assert last["fighter_1"]["rung_out"] and not last["fighter_0"]["rung_out"]
    assert last["fighter_0"]["winner"] == "fighter_0"
    assert not env.agents
    ring_out = env.config.rewards.ring_out
    damage = env.config.rewards.damage * env.config.fighter.kick.damage / env.config.fighter.health
    assert totals["fighter_0"] == pytest.approx(ring_out + damage)
    assert totals["fighter_1"] == pytest.approx(-ring_out - damage)
    assert two.y > env.config.arena.height


def test_a_knock_out_ends_the_fight():
    env, one, two = face_off(10.0)
    two.health = 1.0
    _, infos = run(env, (PUNCH, IDLE), 5)
    assert infos[-1]["fighter_1"]["knocked_out"]
    assert infos[-1]["fighter_0"]["winner"] == "fighter_0"


def test_stocks_respawn_the_loser_until_the_last_one():
    env, one, two = face_off(10.0, stocks=2)
    two.health = 1.0
    _, infos = run(env, (PUNCH, IDLE), 5)
    assert infos[-1]["fighter_1"]["stocks"] == 1
    assert two.health == env.config.fighter.health
    assert env.agents


def test_fighters_standing_idle_stay_put_for_10000_frames():
    env = vooga_env.parallel_env(frame_skip=1, max_cycles=10_000, backend="engine")
    env.reset(seed=0)
    start = [(f.x, f.y) for f in env.fight.fighters]
    run(env, (IDLE, IDLE), 10_000)
    assert env.fight.frame == 10_000
    assert [(f.x, f.y) for f in env.fight.fighters] == start
    assert all(f.vx == 0.0 and f.vy == 0.0 and f.on_ground for f in env.fight.fighters)


def test_jump_lands_back_on_the_stage_and_air_jump_needs_a_second_press():
    env, one, two = face_off(200.0)
    ground = one.y
    run(env, (Action.JUMP, IDLE), 3)
    assert one.y < ground and one.jumps_left == env.config.fighter.air_jumps
    run(env, (IDLE, IDLE), 1)
    run(env, (Action.JUMP, IDLE), 1)
    assert one.jumps_left == env.config.fighter.air_jumps - 1
    run(env, (IDLE, IDLE), 80)
    assert one.y == ground and one.on_ground


def test_nobody_stands_on_the_other_fighters_head():
    env, one, two = face_off(0.0)
    one.x = two.x
    one.y = two.y - one.height - 5.0
    run(env, (IDLE, IDLE), 30)
    assert one.on_ground and two.on_ground
    assert one.right <= two.left or two.right <= one.left


def test_walking_left_for_fighter_1_is_mirrored():
    env, one, two = face_off(200.0)
    x0, x1 = one.x, two.x
    run(env, (Action.LEFT, Action.LEFT), 5)
    assert one.x < x0 and two.x > x1
