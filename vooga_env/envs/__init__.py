"""The env faces: PettingZoo (parallel, AEC), Gymnasium (single fighter, vector), SB3's VecEnv,
and the pygame viewer they render with."""
