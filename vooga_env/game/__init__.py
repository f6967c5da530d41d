"""The fight's rules on the physics engine: actions, config, fighters and hits, the `Fight`,
observations, rewards, outcomes, and the formulas the kernel compiles too (stdlib + numpy)."""
