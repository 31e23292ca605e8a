"""Files written whole or not at all: write to a temporary file next to the target, then rename it
into place (``os.replace`` is atomic within a directory). An interrupted write (an exception,
Ctrl-C) leaves neither a truncated file under the requested name nor the temporary file behind.

Used by :mod:`robokin.demo` (its figure) and the simulator (recordings, CSV logs, screenshots).
"""

from __future__ import annotations

import os
import tempfile


class AtomicPath:
    """A temporary file next to ``path`` (same directory and extension, so writers that look at the
    extension still work) that becomes ``path`` on :meth:`commit` and is removed on :meth:`discard`.

    As a context manager it yields the temporary path and commits when the block ends normally,
    discards when it raises (any exception, KeyboardInterrupt included)::

        with AtomicPath("out/figure.png") as tmp:
            fig.savefig(tmp)

    Args:
        path: The file to write; its directory is created if missing.
    """

    def __init__(self, path) -> None:
        self.path = os.fspath(path)
        directory = os.path.dirname(os.path.abspath(self.path))
        os.makedirs(directory, exist_ok=True)
        stem, ext = os.path.splitext(os.path.basename(self.path))
        fd, self.tmp = tempfile.mkstemp(prefix="." + stem + ".", suffix=".part" + ext, dir=directory)
        os.close(fd)
        # mkstemp makes the file private; give it the permissions a plain open() would.
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(self.tmp, 0o666 & ~umask)

    def commit(self) -> str:
        """Renames the finished temporary file to the target; returns the target's path."""
        os.replace(self.tmp, self.path)
        return self.path

    def discard(self) -> None:
        """Removes the temporary file if it is still there (after a commit it is not)."""
        try:
            os.remove(self.tmp)
        except FileNotFoundError:
            pass

    def __enter__(self) -> str:
        return self.tmp

    def __exit__(self, exc_type, exc, tb) -> None:
        try:
            if exc_type is None:
                self.commit()
        finally:
            self.discard()
