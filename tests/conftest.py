import numpy as np
import pytest


@pytest.fixture
def rng():
    """A seeded generator: every test run sees the same random cases."""
    return np.random.default_rng(20261122)
