"""`SpriteGroupTemplate`: a scene's sprites in teams; only sprites of different teams collide."""

from __future__ import annotations

import numbers
from collections.abc import Iterable, Iterator

from vooga_env.physics.sprites import FighterBody, PlatformBlock, SpriteTemplate


class SpriteGroupTemplate:
    """Teams of sprites. Team order is kept; a sprite belongs to at most one team.

    The usual layout (the original game's): one team for all platforms, one team per fighter, one
    for other sprites. Adding or removing a sprite (a projectile spawned, a fighter split in two)
    is one call.
    """

    def __init__(self) -> None:
        self._teams: list[list[SpriteTemplate]] = []
        self._team_of: dict[SpriteTemplate, int] = {}

    @property
    def teams(self) -> tuple[tuple[SpriteTemplate, ...], ...]:
        return tuple(tuple(team) for team in self._teams)

    def sprites(self) -> Iterator[SpriteTemplate]:
        """Every sprite, team by team."""
        for team in self._teams:
            yield from team

    def __len__(self) -> int:
        return len(self._team_of)

    def __contains__(self, sprite: object) -> bool:
        return sprite in self._team_of

    def team_of(self, sprite: SpriteTemplate) -> int:
        """The index of the team holding `sprite`."""
        try:
            return self._team_of[sprite]
        except KeyError:
            raise ValueError(f"{sprite!r} is not in this group") from None

    def add_platform_block_array(self, blocks: Iterable[PlatformBlock]) -> int:
        """Add all `blocks` as one new team (blocks never collide with each other); its index."""
        return self._add_team(blocks, PlatformBlock, "blocks")

    def add_fighter_sprite_array(self, fighters: Iterable[FighterBody]) -> list[int]:
        """Give each fighter a team of its own; their indices."""
        fighters = list(fighters)
        _check_all(fighters, FighterBody, "fighters")
        return [self._add_team([fighter], FighterBody, "fighters") for fighter in fighters]

    def add_sprite_array(self, sprites: Iterable[SpriteTemplate]) -> int:
        """Add `sprites` as one new team; its index."""
        return self._add_team(sprites, SpriteTemplate, "sprites")

    def add_sprite(self, sprite: SpriteTemplate, team_index: int) -> None:
        """Add one sprite to team `team_index`; `len(teams)` starts a new team."""
        _check_all([sprite], SpriteTemplate, "sprite")
        if isinstance(team_index, bool) or not isinstance(team_index, numbers.Integral):
            raise TypeError(f"team_index must be an int, got {team_index!r}")
        team_index = int(team_index)
        if not 0 <= team_index <= len(self._teams):
            raise IndexError(
                f"team_index must be in 0..{len(self._teams)} (the last starts a new team), "
                f"got {team_index}"
            )
        self._check_new(sprite)
        self._team_of[sprite] = team_index
        if team_index == len(self._teams):
            self._teams.append([])
        self._teams[team_index].append(sprite)

    def remove_sprite(self, sprite: SpriteTemplate) -> None:
        """Take `sprite` out of its team (the team stays, possibly empty, so indices hold)."""
        team_index = self.team_of(sprite)
        self._teams[team_index].remove(sprite)
        del self._team_of[sprite]

    def _add_team(self, sprites: Iterable[SpriteTemplate], kind: type, name: str) -> int:
        sprites = list(sprites)
        _check_all(sprites, kind, name)
        index = len(self._teams)
        for sprite in sprites:
            self._check_new(sprite)
        for sprite in sprites:
            self._team_of[sprite] = index
        self._teams.append(sprites)
        return index

    def _check_new(self, sprite: SpriteTemplate) -> None:
        if sprite in self._team_of:
            raise ValueError(f"{sprite!r} is already in team {self._team_of[sprite]}")


def _check_all(sprites: list[object], kind: type, name: str) -> None:
    for sprite in sprites:
        if not isinstance(sprite, kind):
            raise TypeError(f"{name} must hold {kind.__name__} objects, got {sprite!r}")
    if len({id(sprite) for sprite in sprites}) != len(sprites):
        raise ValueError(f"{name} holds the same sprite twice")
