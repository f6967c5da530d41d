"""`make demo`: a short match between two scripted fighters, told as it happens.

    python -m vooga_env.tools.demo [--left rush] [--right turtle] [--seed 0] [--config default]
                             [--render] [--physics]

`--render` opens a window, or writes demo.gif when there is no display; `--physics` runs the
engine-only scene instead (every collision reaction firing once).
"""

from __future__ import annotations

import argparse
import os

from vooga_env.envs.parallel import parallel_env
from vooga_env.policies import SCRIPTED, make_policy


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--left", default="rush", help=f"fighter_0: one of {', '.join(SCRIPTED)}")
    parser.add_argument("--right", default="turtle", help="fighter_1, likewise")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--config", default="default")
    parser.add_argument("--render", action="store_true", help="window, or demo.gif when headless")
    parser.add_argument("--physics", action="store_true", help="the engine-only scene")
    args = parser.parse_args(argv)
    if args.physics:
        from vooga_env.tools import physics_demo

        physics_demo.main()
        return 0
    try:
        policies = [make_policy(args.left, args.seed), make_policy(args.right, args.seed + 1)]
    except ValueError as error:
        parser.error(str(error))
    headless = args.render and "DISPLAY" not in os.environ
    mode = None if not args.render else ("rgb_array" if headless else "human")
    env = parallel_env(config=args.config, render_mode=mode)
    observations, _ = env.reset(seed=args.seed)
    agents = env.possible_agents
    names = dict(zip(agents, (args.left, args.right)))
    frames = [env.render()] if headless else []
    seconds_per_step = env.config.frame_skip * env.config.physics.frame_time / 1000.0
    print(f"{names[agents[0]]} (fighter_0) vs {names[agents[1]]} (fighter_1) on {env.config.name}")
    step = 0
    while env.agents:
        actions = {
            agent: policy.act(observations[agent]) for agent, policy in zip(agents, policies)
        }
        observations, _, _, _, infos = env.step(actions)
        step += 1
        if headless:
            frames.append(env.render())
        for index, agent in enumerate(agents):
            info, other = infos[agent], agents[1 - index]
            when = f"{step * seconds_per_step:5.2f}s"
            if info["hits_landed"]:
                print(
                    f"{when}  {names[agent]} hits {names[other]}: "
                    f"{infos[other]['health']:.0f} hp left"
                )
            if info["hits_blocked"]:
                print(f"{when}  {names[agent]} blocks")
            if info["rung_out"]:
                print(f"{when}  {names[agent]} is rung out")
            if info["knocked_out"]:
                print(f"{when}  {names[agent]} is knocked out")
    winner = infos[agents[0]]["winner"]
    result = "a draw" if winner == "draw" else f"{names[winner]} ({winner}) wins"
    print(f"after {step} steps ({step * seconds_per_step:.1f}s): {result}")
    if headless:
        from vooga_env.tools.recording import save_animation

        save_animation(frames, "demo.gif", fps=env.metadata["render_fps"])
        print("wrote demo.gif")
    env.close()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
