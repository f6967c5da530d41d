"""The pygame viewer: reads the fight's state and draws it; the fight never reads the viewer.

pygame is imported here only, when a render mode is asked for; `rgb_array` works headless
(SDL_VIDEODRIVER=dummy is set for it when no display is named).
"""

from __future__ import annotations

import os
import warnings
from typing import TYPE_CHECKING, Any

import numpy as np

from vooga_env.game.config import FightConfig
from vooga_env.game.fight import Fight
from vooga_env.game.hits import Fighter

if TYPE_CHECKING:
    import pygame

SKY = (24, 28, 44)
BLAST = (120, 40, 50)
STAGE = (150, 140, 120)
STAGE_EDGE = (200, 190, 165)
FIGHTER_COLOURS = ((220, 70, 70), (70, 130, 230))
HITBOX = (255, 220, 60)
TEXT = (235, 235, 235)


def frames_per_second(config: FightConfig) -> int:
    """Env steps per second of game time: what a window shows in real time."""
    return round(1000.0 / (config.physics.frame_time * config.frame_skip))


HEADLESS_DRIVERS = ("dummy", "offscreen")


def warn_if_headless(driver: str) -> None:
    """Say (once: a warning) that a human-mode window goes nowhere, rather than run blind."""
    if driver in HEADLESS_DRIVERS:
        warnings.warn(
            f"render_mode='human' but pygame found no display (video driver {driver!r}): nothing "
            "is shown. Set DISPLAY (or run under xvfb-run), or use render_mode='rgb_array'.",
            RuntimeWarning,
            stacklevel=3,
        )


class Viewer:
    """Draws a Fight to an off-screen surface, and to a window in `human` mode."""

    def __init__(
        self, fight: Fight, mode: str, fps: float, names: tuple[str, str] | None = None
    ) -> None:
        if mode == "rgb_array" and "DISPLAY" not in os.environ:
            os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
        try:
            import pygame
        except ImportError:
            raise ImportError("rendering needs pygame: pip install 'vooga-env[render]'") from None
        self.pygame = pygame
        self.fight = fight
        self.mode = mode
        self.fps = fps
        self.names = names or tuple(fighter.name for fighter in fight.fighters)
        """The HUD's label of each fighter (default `fighter_0`, `fighter_1`)."""
        arena = fight.config.arena
        self.size = (int(arena.width), int(arena.height))
        pygame.font.init()  # not pygame.init(): that opens the audio device too, for nothing
        self.surface = pygame.Surface(self.size)
        self.font = pygame.font.Font(None, 22)
        self.window = None
        self.clock = None
        if mode == "human":
            pygame.display.init()
            self.window = pygame.display.set_mode(self.size)
            pygame.display.set_caption("vooga_env")
            self.clock = pygame.time.Clock()
            warn_if_headless(pygame.display.get_driver())

    def draw(self) -> np.ndarray | None:
        """Draw the current frame; an HxWx3 uint8 array in rgb_array mode, None in human mode."""
        pygame, surface = self.pygame, self.paint()
        if self.window is not None:
            pygame.event.pump()
            self.window.blit(surface, (0, 0))
            pygame.display.flip()
            self.clock.tick(self.fps)
            return None
        return np.ascontiguousarray(pygame.surfarray.pixels3d(surface).transpose(1, 0, 2))

    def paint(self) -> pygame.Surface:
        """Draw the current frame on the off-screen surface and return it (a caller's window)."""
        pygame, surface, fight = self.pygame, self.surface, self.fight
        surface.fill(SKY)
        width, height = self.size
        pygame.draw.rect(surface, BLAST, (0, height - 4, width, 4))
        for block in fight.blocks:
            rect = pygame.Rect(
                round(block.x), round(block.y), round(block.width), round(block.height)
            )
            pygame.draw.rect(surface, STAGE, rect)
            pygame.draw.rect(surface, STAGE_EDGE, (rect.x, rect.y, rect.width, 3))
        for fighter in fight.fighters:
            self._fighter(fighter)
        self._hud()
        return surface

    def _fighter(self, fighter: Fighter) -> None:
        pygame, surface = self.pygame, self.surface
        colour = FIGHTER_COLOURS[fighter.index]
        if fighter.hitstun > 0 and fighter.hitstun % 2:
            colour = (255, 255, 255)
        body = pygame.Rect(
            round(fighter.x), round(fighter.y), round(fighter.width), round(fighter.height)
        )
        pygame.draw.rect(surface, colour, body, border_radius=6)
        eye_x = body.centerx + int(fighter.facing * body.width * 0.25)
        pygame.draw.circle(surface, (255, 255, 255), (eye_x, body.y + 12), 5)
        pygame.draw.circle(surface, (20, 20, 20), (eye_x + int(fighter.facing * 2), body.y + 12), 2)
        if fighter.blocking:
            shield_x = body.right + 3 if fighter.facing > 0 else body.left - 9
            pygame.draw.rect(
                surface, (160, 230, 255), (shield_x, body.y, 6, body.height), border_radius=3
            )
        hitbox = fighter.hitbox
        if hitbox.active:
            rect = (round(hitbox.x), round(hitbox.y), round(hitbox.width), round(hitbox.height))
            pygame.draw.rect(surface, HITBOX, rect)
        elif fighter.move is not None:
            arm_y = body.y + 20
            arm_x = body.right if fighter.facing > 0 else body.left - 8
            pygame.draw.rect(surface, colour, (arm_x, arm_y, 8, 6))

    def _hud(self) -> None:
        pygame, surface, fight = self.pygame, self.surface, self.fight
        width = self.size[0]
        for fighter in fight.fighters:
            left = 20 if fighter.index == 0 else width - 220
            share = max(fighter.health, 0.0) / fighter.config.health
            pygame.draw.rect(surface, (60, 60, 70), (left, 16, 200, 14))
            pygame.draw.rect(
                surface, FIGHTER_COLOURS[fighter.index], (left, 16, round(200 * share), 14)
            )
            label = f"{self.names[fighter.index]}  {fighter.health:.0f} hp  stocks {fighter.stocks}"
            text = self.font.render(label, True, TEXT)
            place = (
                {"topleft": (left, 34)} if fighter.index == 0 else {"topright": (width - 20, 34)}
            )
            surface.blit(text, text.get_rect(**place))
        seconds = (fight.config.max_cycles - fight.steps) * fight.config.frame_skip
        seconds *= fight.config.physics.frame_time / 1000.0
        timer = self.font.render(f"{seconds:5.1f}s", True, TEXT)
        surface.blit(timer, timer.get_rect(midtop=(width // 2, 14)))

    def close(self) -> None:
        if self.window is not None:
            self.pygame.display.quit()
            self.window = None


class LazyViewer:
    """The `Viewer` of an engine simulation's fight, made at the first frame (pygame is imported
    only then) and left out of a pickle (pygame surfaces don't pickle; a copy draws afresh)."""

    def __init__(self, simulation: Any, mode: str, fps: int) -> None:
        self.simulation = simulation
        self.mode = mode
        self.fps = fps
        self.viewer: Viewer | None = None

    def draw(self) -> np.ndarray:
        if self.viewer is None:
            self.viewer = Viewer(self.simulation.fight, self.mode, self.fps)
        return self.viewer.draw()

    def close(self) -> None:
        if self.viewer is not None:
            self.viewer.close()
            self.viewer = None

    def __getstate__(self) -> dict[str, Any]:
        return {**self.__dict__, "viewer": None}
