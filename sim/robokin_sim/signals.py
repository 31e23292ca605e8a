"""How a run stops on a signal: SIGINT (Ctrl-C), SIGTERM (``kill``, ``timeout``, a container stop)
and SIGHUP (the terminal closed) all stop it the same way, within a second, and lose nothing.

Once the run's outputs are open (:func:`deferred`), the handler only notes the signal; the loop
looks at :func:`requested` once per frame, leaves at the frame's end and finishes the log, the
recording and the screenshot as a run ended by ``esc`` does (every row logged so far, a recording
closed properly), and ``robokin-sim`` names them on one line and exits with status 128 + the
signal's number (130, 143, 129). A signal that comes earlier (while pygame or the scene starts)
raises :class:`Stopped` at once: nothing had been written yet. Later signals are ignored while the
run finishes. Only SIGKILL can lose the outputs; its temporary files are removed by the next run
(:mod:`robokin.files`). SDL's own handlers, which turn SIGINT and SIGTERM into a quit event, are
turned off by the loop.
"""

from __future__ import annotations

import contextlib
import signal
from typing import Iterator, Optional

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


class _State:
    """The signal received (None: none yet) and whether the handler only notes it."""

    signum: Optional[int] = None
    deferring: bool = False


_STATE = _State()


def requested() -> Optional[int]:
    """The number of the signal that asked the run to stop, or None."""
    return _STATE.signum


@contextlib.contextmanager
def deferred() -> Iterator[None]:
    """Within the block a signal is only noted (:func:`requested`): the caller stops at a point of
    its choosing, with its files whole. Outside :func:`stop_on_signals` it changes nothing."""
    before = _STATE.deferring
    _STATE.deferring = True
    try:
        yield
    finally:
        _STATE.deferring = before


@contextlib.contextmanager
def stop_on_signals() -> Iterator[None]:
    """Within the block, SIGINT, SIGTERM and SIGHUP stop the run: noted inside :func:`deferred`,
    else raised as :class:`Stopped` (the first one; later ones are ignored while the run finishes).
    The previous handlers come back afterwards, and :func:`requested` is None again."""
    previous = {}
    _STATE.signum = None

    def handler(signum, frame):
        if _STATE.signum is not None:  # already stopping: let the run finish its files
            return
        _STATE.signum = signum
        if not _STATE.deferring:
            raise Stopped(signum)

    try:
        for sig in SIGNALS:
            previous[sig] = signal.signal(sig, handler)
        yield
    finally:
        for sig, old in previous.items():
            signal.signal(sig, old if old is not None else signal.SIG_DFL)
        _STATE.signum = None
