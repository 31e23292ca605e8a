import os
import signal

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, settings

# How many examples each property test runs. `make test` (CI) uses "ci": a fixed sequence, so that
# a landing is reproducible; `make fuzz` uses "fuzz": ten times as many, freshly random each run;
# `make test-asan` uses "asan": fewer, since the sanitizer build is several times slower;
# `make mutate` uses "mutate": the examples of "ci" without shrinking a failure (only whether a
# planted bug is caught matters there, not its smallest example).
_COMMON = dict(deadline=None, print_blob=True,
               suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much])
settings.register_profile("ci", max_examples=300, derandomize=True, **_COMMON)
settings.register_profile("fuzz", max_examples=3000, **_COMMON)
settings.register_profile("asan", max_examples=60, derandomize=True, **_COMMON)
settings.register_profile("mutate", max_examples=300, derandomize=True,
                          phases=[Phase.explicit, Phase.reuse, Phase.generate], **_COMMON)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

# A suite started in the background by a shell without job control (`make test &` in a script)
# inherits Ctrl-C ignored, and Python then installs no KeyboardInterrupt handler, neither here nor
# in the interpreters the tests start (an ignored signal stays ignored across exec). The tests of
# Ctrl-C need Python's own handler, as a user's interpreter has it.
if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)


@pytest.fixture
def rng():
    """A seeded generator: every test run sees the same random cases."""
    return np.random.default_rng(20261122)


@pytest.fixture(autouse=True)
def _module_rng_restarted(request):
    """A module's generator RNG restarted from its RNG_SEED before each of its tests: the cases a
    test sees never depend on which tests ran before it in its process (`make test` spreads a
    module's tests over several, in any order)."""
    module = request.module
    if hasattr(module, "RNG_SEED"):
        module.RNG = np.random.default_rng(module.RNG_SEED)
