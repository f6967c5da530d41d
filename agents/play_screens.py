"""What `agents.play` draws over the fight: the countdown, the key help, the pause screen and the
round and match results. It reads the `Game`; the game never reads the screens."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pygame

from vooga_env.envs.render import FIGHTER_COLOURS, TEXT, Viewer

from .play_keys import CONTROL_HELP, FIGHT_HELP
from .play_loop import Game, Phase

DIM = (90, 90, 100)
GOLD = (250, 210, 80)
PANEL = (10, 12, 20)
BANNER_MS = 700.0
"""How long "FIGHT!" shows once the countdown is over."""
MAX_ROUND_LINES = 6
"""The match result lists at most this many rounds (the last ones)."""


class Screens:
    """Draws the game on `surface` (a window's, or an off-screen one for tests and screenshots)."""

    def __init__(self, game: Game, surface: pygame.Surface) -> None:
        self.game = game
        self.surface = surface
        seat = game.settings.seat
        self.names = ("you", game.opponent_name) if seat == 0 else (game.opponent_name, "you")
        self.viewer = Viewer(game.env.fight, "rgb_array", game.fps, names=self.names)
        height = surface.get_height()
        self.big = pygame.font.Font(None, max(48, height // 5))
        self.medium = pygame.font.Font(None, max(28, height // 14))
        self.small = pygame.font.Font(None, max(20, height // 24))
        self.boxes: list[pygame.Rect] = []
        """Where this frame's texts and panels went (a test checks that none overlap)."""

    def draw(self) -> None:
        game, surface = self.game, self.surface
        surface.blit(self.viewer.paint(), (0, 0))
        self.boxes = []
        if game.phase in (Phase.COUNTDOWN, Phase.FIGHT):
            self._round_line()
        if game.help_visible and game.phase in (Phase.COUNTDOWN, Phase.FIGHT):
            self._mark_player()
        if game.paused:
            self._paused()
        elif game.phase is Phase.COUNTDOWN:
            self._countdown()
        elif game.phase is Phase.FIGHT:
            if game.phase_ms < BANNER_MS:
                self._text("FIGHT!", self.big, GOLD, center=self._at(0.5, 0.4))
            self._help() if game.help_visible else self._hint()
        elif game.phase is Phase.ROUND_OVER:
            self._round_over()
        elif game.phase is Phase.MATCH_OVER:
            self._match_over()

    # -- the screens -----------------------------------------------------------------------

    def _round_line(self) -> None:
        """The round and the match score under the timer, in a match of several rounds."""
        game = self.game
        rounds = game.settings.rounds
        if rounds == 1:
            return
        you, them = game.match.count("win"), game.match.count("loss")
        text = f"round {game.round_number} of {rounds}   you {you} - {them} {game.opponent_name}"
        self._text(text, self.small, TEXT, midtop=self._at(0.5, 0.12))

    def _countdown(self) -> None:
        game, settings = self.game, self.game.settings
        self._shade(90)
        stocks = game.env.config.stocks
        about = f"{stocks} stock{'s' * (stocks != 1)} each"
        if settings.rounds > 1:
            first_to = f"first to {settings.wins_needed} wins"
            about = f"round {game.round_number}  ·  {first_to}  ·  {about}"
        left = max(settings.countdown_ms - game.phase_ms, 0.0)
        number = self.big.render(str(int(left // 1000) + 1), True, GOLD)
        self._card([self._versus(), self.small.render(about, True, TEXT), number])
        self._help()

    def _paused(self) -> None:
        self._shade(150)
        keys = "P: resume      R: restart the match      Esc: quit"
        self._card([self.big.render("PAUSED", True, GOLD), self.small.render(keys, True, TEXT)])
        self._help()

    def _round_over(self) -> None:
        result = self.game.match.rounds[-1]
        self._shade(120)
        headline, colour = self._verdict(result.outcome, f"round {result.number}")
        how = self._how(result.outcome, result.how)
        self._card(
            [
                self.medium.render(headline, True, colour),
                self.small.render(how, True, TEXT),
                self._score(),
            ]
        )
        self._prompt("Enter or Space: next round      R: restart      Esc: quit")

    def _match_over(self) -> None:
        game = self.game
        match = game.match
        self._shade(150)
        headline, colour = self._verdict(match.outcome, "the match")
        lines = [self.medium.render(headline, True, colour), self._score()]
        for result in match.rounds[-MAX_ROUND_LINES:]:
            winner = {"win": "you", "loss": game.opponent_name}.get(result.outcome, "draw")
            text = f"round {result.number}: {winner} ({result.how}, {result.steps} steps)"
            lines.append(self.small.render(text, True, TEXT))
        self._card(lines)
        self._prompt("R or Enter: play again      Esc: quit")

    # -- parts -----------------------------------------------------------------------------

    def _versus(self) -> pygame.Surface:
        """Both fighters' names in their colours: "you  vs  rush"."""
        parts = [
            self.medium.render(self.names[0], True, FIGHTER_COLOURS[0]),
            self.medium.render("   vs   ", True, TEXT),
            self.medium.render(self.names[1], True, FIGHTER_COLOURS[1]),
        ]
        line = pygame.Surface(
            (sum(part.get_width() for part in parts), max(p.get_height() for p in parts)),
            pygame.SRCALPHA,
        )
        x = 0
        for part in parts:
            line.blit(part, (x, 0))
            x += part.get_width()
        return line

    def _verdict(self, outcome: str, what: str) -> tuple[str, tuple[int, int, int]]:
        seat = self.game.settings.seat
        if outcome == "win":
            return f"You win {what}!", FIGHTER_COLOURS[seat]
        if outcome == "loss":
            return f"{self.game.opponent_name} wins {what}", FIGHTER_COLOURS[1 - seat]
        return f"{what[0].upper()}{what[1:]}: a draw", TEXT

    def _how(self, outcome: str, how: str) -> str:
        """How the round ended, in a sentence: who was rung out, or who led when time ran out."""
        winner, loser = {"win": ("you", self.game.opponent_name)}.get(
            outcome, (self.game.opponent_name, "you")
        )
        if how == "ring-out":
            return f"{loser}: rung out"
        if how == "KO":
            return f"{loser}: knocked out"
        if outcome == "draw":
            return "time up: level on stocks and health"
        return f"time up: {winner} had {how.removeprefix('time up, ')}"

    def _score(self) -> pygame.Surface:
        match = self.game.match
        score = f"you {match.count('win')} - {match.count('loss')} {self.game.opponent_name}"
        if match.count("draw"):
            score += f"   ({match.count('draw')} drawn)"
        return self.medium.render(score, True, TEXT)

    def _prompt(self, text: str) -> None:
        """The result screen's keys (once it takes them) and where the last replay went."""
        lines = [(text, GOLD if self.game.accepts_keys else DIM)]
        saved = self.game.last_saved
        if saved is not None:
            lines.append((f"replay: {_short(saved)}", TEXT))
        self._panel(lines)

    def _help(self) -> None:
        """The key help in a panel at the bottom, below the stage."""
        self._panel([(line, TEXT) for line in (*FIGHT_HELP, CONTROL_HELP)])

    def _mark_player(self) -> None:
        """ "you" over the person's fighter, until the first key."""
        fighter = self.game.env.fight.fighters[self.game.settings.seat]
        centre = (round(fighter.x + fighter.width / 2), round(fighter.y) - 6)
        mark = self.small.render("you", True, FIGHTER_COLOURS[fighter.index])
        self.surface.blit(mark, mark.get_rect(midbottom=centre))  # moves with it: not a box

    def _card(self, lines: list[pygame.Surface]) -> None:
        """Rendered lines, centred in a dark card in the upper middle (clear of any stage)."""
        gap = self.small.get_linesize() // 2
        width = max(line.get_width() for line in lines) + 4 * gap
        height = sum(line.get_height() for line in lines) + gap * (len(lines) + 1)
        surface = self.surface
        top = max(round(surface.get_height() * 0.4 - height / 2), 3 * self.small.get_linesize())
        card = pygame.Rect(0, top, width, height)
        card.centerx = surface.get_width() // 2
        pygame.draw.rect(surface, PANEL, card, border_radius=10)
        self.boxes.append(card)
        y = card.top + gap
        for line in lines:
            surface.blit(line, line.get_rect(midtop=(card.centerx, y)))
            y += line.get_height() + gap

    def _panel(self, lines: list[tuple[str, Any]]) -> None:
        """Lines of text, centred in a dark panel at the bottom of the surface."""
        rendered = [self.small.render(line, True, colour) for line, colour in lines]
        step = self.small.get_linesize()
        width = max(text.get_width() for text in rendered) + 24
        height = step * len(rendered) + 12
        panel = pygame.Surface((width, height), pygame.SRCALPHA)
        panel.fill((*PANEL, 200))
        surface = self.surface
        box = panel.get_rect(midbottom=(surface.get_width() // 2, surface.get_height() - 6))
        surface.blit(panel, box)
        self.boxes.append(box)
        for row, text in enumerate(rendered):
            surface.blit(text, text.get_rect(midtop=(box.centerx, box.top + 6 + row * step)))

    def _hint(self) -> None:
        width, height = self.surface.get_size()
        self._text(CONTROL_HELP, self.small, DIM, bottomright=(width - 10, height - 8))

    def _shade(self, alpha: int) -> None:
        shade = pygame.Surface(self.surface.get_size(), pygame.SRCALPHA)
        shade.fill((*PANEL, alpha))
        self.surface.blit(shade, (0, 0))

    def _text(self, text: str, font: pygame.font.Font, colour: Any, **anchor: Any) -> None:
        rendered = font.render(text, True, colour)
        box = rendered.get_rect(**anchor)
        self.surface.blit(rendered, box)
        self.boxes.append(box)

    def _at(self, x: float, y: float) -> tuple[int, int]:
        """A point at fractions of the surface's width and height."""
        return round(self.surface.get_width() * x), round(self.surface.get_height() * y)


def _short(path: Any) -> str:
    """A path as the person typed it when relative, else its last two parts."""
    path = Path(path)
    return str(path) if not path.is_absolute() else str(Path(*path.parts[-2:]))
