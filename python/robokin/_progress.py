"""The progress bar of robokin's long calls (batch FK and IK, path tracking, workspace maps,
design studies, planning).

The core calls :meth:`Bar.update` about every 50 ms while such a call runs. The bar shows only on
an interactive terminal and only once the call has run for more than :data:`DELAY` seconds, so
short calls, scripts writing to files and notebooks see nothing.
"""

import sys

DELAY = 2.0  # seconds a call runs before its bar appears
WIDTH = 30  # characters of the bar itself


def _interactive(stream) -> bool:
    try:
        return stream is not None and stream.isatty()
    except (AttributeError, ValueError):  # no isatty, or a closed stream
        return False


class Bar:
    """One call's bar on ``sys.stderr``, redrawn in place."""

    def __init__(self, what: str) -> None:
        self.what = what
        self.shown = False
        self.last = (0, 1, 0.0)

    def update(self, done: int, total: int, elapsed: float) -> None:
        self.last = (done, total, elapsed)
        if elapsed >= DELAY and _interactive(sys.stderr):
            self._draw(done, total, elapsed, end="")

    def close(self, completed: bool) -> None:
        """Ends the bar's line: at 100 % when the call completed, where it stood otherwise."""
        if not self.shown:
            return
        done, total, elapsed = self.last
        self._draw(total if completed else done, total, elapsed, end="\n")

    def _draw(self, done: int, total: int, elapsed: float, end: str) -> None:
        share = min(1.0, done / total) if total > 0 else 1.0
        filled = int(round(WIDTH * share))
        left = f", {elapsed * (1 - share) / share:.0f} s left" if 0 < share < 1 else ""
        line = f"\r{self.what}: [{'#' * filled}{'.' * (WIDTH - filled)}] {100 * share:3.0f}% ({elapsed:.0f} s{left})"
        sys.stderr.write(line + end)
        sys.stderr.flush()
        self.shown = True
