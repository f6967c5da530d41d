"""What is built on the envs: matches and their records, Elo, replays, recordings, styles, demos."""
