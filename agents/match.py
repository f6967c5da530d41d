"""Play two policies against each other, or play a replay back.

    python -m agents.match rush turtle --episodes 200 --seed 0 --config default
    python -m agents.match rush runs/model.zip --record first.gif --save-replay first.json
    python -m agents.match --replay first.json --render

Each side is a scripted fighter (idle, random, rush, turtle, zoner, edge_guard) or a saved model
(.zip, or an exported fighter .npz). Seats are swapped every game and both games of a pair share
their seeds, so neither side is favoured. `--record` (.gif or .mp4) and `--save-replay` keep the
first game.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from vooga_env.tools.match import MatchResult, run_match
from vooga_env.tools.recording import check_writer, save_animation
from vooga_env.tools.replay import Replay, ReplayError, ReplayMismatch, play_back

from . import common


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="vooga-match",
        description="Play policy A against policy B (seats swapped each game), or a replay back.",
    )
    parser.add_argument(
        "policies",
        nargs="*",
        metavar="POLICY",
        help="two policies: scripted names or saved model paths (.zip)",
    )
    common.add_fight_options(parser, episodes=100)
    parser.add_argument("--render", action="store_true", help="watch the games in a window")
    parser.add_argument("--record", metavar="FILE", help="save the first game as a .gif or .mp4")
    parser.add_argument(
        "--record-scale",
        type=int,
        default=1,
        metavar="N",
        help="keep every N-th pixel in the recording (2: half size)",
    )
    parser.add_argument("--save-replay", metavar="FILE", help="save the first game as a replay")
    parser.add_argument("--replay", metavar="FILE", help="play a replay file back and check it")
    common.add_output_options(parser)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.record:
        try:
            check_writer(args.record)
        except (ValueError, ImportError) as error:
            parser.error(f"--record: {error}")
    if args.record_scale < 1:
        parser.error(f"--record-scale {args.record_scale} is not allowed: must be >= 1")
    for flag, path in (("--record", args.record), ("--save-replay", args.save_replay)):
        if path:
            common.check_output(parser, flag, path)
    if args.replay:
        if args.policies:
            parser.error("--replay plays a file back; give no policies with it")
        return _replay(parser, args)
    if len(args.policies) != 2:
        parser.error(f"give two policies (got {len(args.policies)}), or --replay FILE")
    config = common.fight_config(parser, args)
    policies = [common.policy(parser, spec) for spec in args.policies]
    names = _names(policies[0].name, policies[1].name)
    advance, close = common.progress_bar(
        args.episodes, not args.no_progress, f"{names[0]} vs {names[1]}"
    )
    try:
        result = run_match(
            policies[0],
            policies[1],
            args.episodes,
            args.seed,
            config,
            render_mode="human" if args.render else None,
            names=names,
            record_actions=bool(args.save_replay),
            record_frames=1 if args.record else 0,
            progress=advance,
            step_hook=common.stop_on_window_close if args.render else None,
        )
    except common.WindowClosed:
        print("window closed: match stopped", file=sys.stderr)
        return 0
    finally:
        close()
    result.check()
    output = result.to_dict()
    if args.record:
        first = result.episodes[0]
        save_animation(first.frames, args.record, common.fps(config), args.record_scale)
        output["record"] = args.record
    if args.save_replay:
        Replay.from_episode(result.episodes[0], config).save(args.save_replay)
        output["replay"] = args.save_replay
    if args.json:
        common.print_json(output)
    else:
        print(format_result(result))
        for key, what in (("record", "recording"), ("replay", "replay")):
            if key in output:
                print(f"{what} of the first game: {output[key]}")
    return 0


def format_result(result: MatchResult) -> str:
    """The match table, under a line that says what was played."""
    config = result.config
    head = (
        f"{result.names[0]} vs {result.names[1]}: {result.games} games, config {config.name} "
        f"(max_cycles {config.max_cycles}), seed {result.seed}, seats swapped each game"
    )
    headers = (
        "policy",
        "wins",
        "losses",
        "draws",
        "ring-outs",
        "KOs",
        "mean damage",
        "mean length",
    )
    rows = [
        (
            side.name,
            side.wins,
            side.losses,
            side.draws,
            side.ring_outs,
            side.kos,
            side.mean_damage,
            result.mean_length,
        )
        for side in result.sides
    ]
    return head + "\n" + common.table(headers, rows)


def _replay(parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
    try:
        replay = Replay.load(args.replay)
    except ReplayError as error:
        parser.error(str(error))
    render_mode = "human" if args.render else ("rgb_array" if args.record else None)
    try:
        record = play_back(
            replay,
            render_mode,
            record_frames=bool(args.record),
            step_hook=common.stop_on_window_close if args.render else None,
        )
    except common.WindowClosed:
        print("window closed: playback stopped", file=sys.stderr)
        return 0
    except ReplayMismatch as error:
        print(f"error: {args.replay}: {error}", file=sys.stderr)
        return 1
    if args.record:
        save_animation(record.frames, args.record, common.fps(replay.config), args.record_scale)
    output = {
        "replay": args.replay,
        "names": list(replay.names),
        "config": replay.config.name,
        "seed": replay.seed,
        "steps": record.steps,
        "winner": record.winner,
        "matches_recording": bool(replay.result or replay.digests),
        "checked": "every step" if replay.digests else ("the result" if replay.result else "none"),
        "result": {"health": record.health, "stocks": record.stocks, "positions": record.positions},
    }
    if args.record:
        output["record"] = args.record
    if args.json:
        common.print_json(output)
    else:
        winner = record.winner if record.winner else "none (stopped early)"
        print(
            f"replay {args.replay}: {replay.names[0]} (fighter_0) vs "
            f"{replay.names[1]} (fighter_1), "
            f"config {replay.config.name}, seed {replay.seed}\n"
            f"{record.steps} steps, winner {winner}; "
            + (
                "the playback matches the recording at every step"
                if replay.digests
                else "the playback matches the recorded result (a version 1 replay: no digests)"
                if replay.result
                else "nothing recorded to check against"
            )
        )
        if args.record:
            print(f"recording: {args.record}")
    return 0


def _names(a: str, b: str) -> tuple[str, str]:
    """The two sides' labels, told apart when both are the same policy."""
    return (a, b) if a != b else (f"{a} (A)", f"{b} (B)")


if __name__ == "__main__":
    sys.exit(main())
