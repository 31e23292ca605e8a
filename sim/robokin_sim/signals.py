"""How a run stops on a signal: SIGINT (Ctrl-C), SIGTERM (``kill``, ``timeout``, a container stop)
and SIGHUP (the terminal closed) all stop it the same way, within a second.

The handler raises :class:`Stopped` in the main thread; the loop discards what it was writing (the
log, the recording and the screenshot are written only by a run that ends, by its frame budget,
``esc`` or the window's close button), files that existed under those names are left as they were,
and ``robokin-sim`` exits with status 128 + the signal's number (130, 143, 129). SDL's own
handlers, which turn SIGINT and SIGTERM into a quit event, are turned off by the loop.
"""

from __future__ import annotations

import contextlib
import signal
from typing import Iterator

#: The signals that stop a run.
SIGNALS = tuple(getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name))


class Stopped(BaseException):
    """A signal asked the run to stop (a BaseException, like KeyboardInterrupt: no ``except
    Exception`` swallows it)."""

    def __init__(self, signum: int) -> None:
        self.signum = int(signum)
        super().__init__(f"stopped by {signal.Signals(self.signum).name}")

    @property
    def name(self) -> str:
        return signal.Signals(self.signum).name

    @property
    def status(self) -> int:
        """The exit status: 128 + the signal's number."""
        return 128 + self.signum


@contextlib.contextmanager
def stop_on_signals() -> Iterator[None]:
    """Within the block, SIGINT, SIGTERM and SIGHUP raise :class:`Stopped` (the first one; later
    ones are ignored while the run cleans up). The previous handlers come back afterwards."""
    previous = {}
    fired = []

    def handler(signum, frame):
        if fired:  # already stopping: let the clean-up finish
            return
        fired.append(signum)
        raise Stopped(signum)

    try:
        for sig in SIGNALS:
            previous[sig] = signal.signal(sig, handler)
        yield
    finally:
        for sig, old in previous.items():
            signal.signal(sig, old if old is not None else signal.SIG_DFL)
