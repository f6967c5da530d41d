"""The policy interface: wrapping and seeding a policy that already exists."""

import numpy as np

from vooga_env.policies import make_policy


def test_a_policy_given_with_a_seed_is_a_reseeded_copy():
    original = make_policy("random", 1)
    before = original.rng.bit_generator.state
    first, second = make_policy(original, 7), make_policy(original, 7)
    assert first is not original and second is not first
    assert original.rng.bit_generator.state == before  # a shared original is left alone
    observation = np.zeros(41, dtype=np.float32)
    assert [first.act(observation) for _ in range(50)] == [
        second.act(observation) for _ in range(50)
    ]
    assert make_policy(original) is original  # no seed: the policy itself
