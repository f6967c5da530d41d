"""What users see: an rgb frame with the stage, both fighters and the HUD."""

import numpy as np

import vooga_env
from vooga_env.envs.render import FIGHTER_COLOURS, STAGE


def test_rgb_frame_shows_stage_and_both_fighters():
    env = vooga_env.parallel_env(render_mode="rgb_array")
    env.reset(seed=0)
    frame = env.render()
    assert frame.shape == (480, 800, 3) and frame.dtype == np.uint8
    for colour in (STAGE, *FIGHTER_COLOURS):
        assert np.all(frame == colour, axis=-1).sum() > 500
    block = env.fight.blocks[0]
    assert tuple(frame[int(block.y) + 10, int(block.x) + 10]) == STAGE
    env.close()


def test_frames_change_as_the_fight_goes_on():
    env = vooga_env.parallel_env(render_mode="rgb_array")
    env.reset(seed=0)
    first = env.render()
    for _ in range(10):
        env.step({"fighter_0": 2, "fighter_1": 2})
    assert not np.array_equal(first, env.render())


def test_rendering_frames_opens_no_audio_device_and_no_window():
    import pygame

    pygame.quit()  # whatever an earlier test opened
    env = vooga_env.parallel_env(render_mode="rgb_array")
    env.reset(seed=0)
    env.render()
    assert pygame.mixer.get_init() is None
    assert not pygame.display.get_init()
    env.close()
