"""`bench.argmax_stalemate`: the standing-still steps found in real fights, a move put in their
place, and the command on a saved model."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")


from bench.argmax_stalemate import MOVES, Replaced, main  # noqa: E402
from vooga_env.game.actions import Action  # noqa: E402
from vooga_env.policies.models import MLPPolicy  # noqa: E402
from vooga_env.tools.batch_match import batch_match  # noqa: E402


def walker() -> MLPPolicy:
    """An MLP fighter that only walks toward its opponent (its one layer's bias picks RIGHT in
    the opponent-facing frame)."""
    bias = np.zeros(len(Action))
    bias[Action.RIGHT] = 1.0
    return MLPPolicy([(np.zeros((41, len(Action))), bias)], "tanh", "walker", True, "opponent")


def test_a_walker_pushing_shover_stands_still_until_a_punch_replaces_the_walk():
    kept = Replaced(walker(), None)
    result = batch_match(kept, "shover", 8, seed=5)
    assert result["draws"] == 8  # both push, neither moves: every game runs out of time
    assert kept.still_steps / kept.steps > 0.9
    probabilities = kept.probabilities / kept.still_steps
    assert probabilities.argmax() == Action.RIGHT and probabilities.sum() == pytest.approx(1.0)
    punching = Replaced(walker(), Action.PUNCH)
    assert batch_match(punching, "shover", 8, seed=5)["wins"] == 8
    assert punching.still_steps < kept.still_steps


def test_a_walker_against_rush_hardly_stands_still():
    """Rush attacks on contact: a step or so of pushing before its blow, not whole games."""
    kept = Replaced(walker(), None)
    batch_match(kept, "rush", 8, seed=5)
    assert kept.still_steps / kept.steps < 0.05


def test_the_command_prints_every_move_against_each_opponent(tiny_model, capsys):
    argv = [str(tiny_model), "--against", "shover", str(tiny_model)]
    assert main([*argv, "--games", "2"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].split()[:3] == ["opponent", "still", "walk"]
    assert [line.split()[0] for line in lines[1:]] == ["shover", "tiny"]
    for line in lines[1:]:
        results = line.split()[3:]
        assert len(results) == len(MOVES)
        assert all(sum(map(int, cell.split("/"))) == 2 for cell in results)


def test_a_missing_model_or_an_unknown_opponent_is_refused_by_name(tmp_path, capsys):
    with pytest.raises(SystemExit):
        main([str(tmp_path / "model.zip")])
    assert f"model '{tmp_path / 'model.zip'}': no such file" in capsys.readouterr().err
    (tmp_path / "model.zip").write_bytes(b"")
    with pytest.raises(SystemExit):
        main([str(tmp_path / "model.zip"), "--against", "nobody"])
    error = capsys.readouterr().err
    assert "--against 'nobody': neither a scripted fighter" in error and "shover" in error
