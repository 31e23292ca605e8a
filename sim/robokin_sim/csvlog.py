"""The CSV log: one row per simulation step with the columns of DESIGN.md.

Floats are written with ``repr`` (shortest round-trip form), so a test reading the log sees the
exact values the simulator had. The file is written under a temporary name
(``.NAME.PID.RANDOM.part.csv`` next to it) and renamed when closed; with ``flush`` every row
reaches that temporary file at once, so a window run's log can be followed while it runs.

A run killed outright (SIGKILL) leaves its temporary file; the next log of the same name keeps
that file's complete rows as ``NAME.partial.csv`` (:func:`robokin.files.keep_stale`) rather than
removing them, and names what it kept in :attr:`CsvLog.kept`.
"""

from __future__ import annotations

import csv
from typing import Optional, Sequence

from robokin.files import AtomicPath, keep_stale

from .outputs import OutputError, reason_of


class CsvLog:
    """Writes rows under a header.

    Args:
        path: The CSV file to write.
        columns: The header.
        flush: Flush every row to the temporary file.
    """

    def __init__(self, path: str, columns: Sequence[str], flush: bool = False) -> None:
        self.path = path
        self.columns = tuple(columns)
        self.rows = 0
        self.flush = bool(flush)
        self.kept = keep_stale(path)
        self._out = AtomicPath(path)
        self._written: Optional[str] = None
        self._file = open(self._out.tmp, "w", newline="", encoding="utf-8")
        self._writer = csv.writer(self._file, lineterminator="\n")
        self.write(self.columns, header=True)

    @property
    def tmp(self) -> str:
        """The temporary file the rows go to until :meth:`close`."""
        return self._out.tmp

    def write(self, row: Sequence, header: bool = False) -> None:
        """Appends one row (as many values as columns); OutputError when the disk refuses it."""
        try:
            self._writer.writerow(row)
            if self.flush:
                self._file.flush()
        except OSError as exc:
            raise OutputError(self.path, reason_of(exc)) from None
        if not header:
            self.rows += 1

    def close(self) -> Optional[str]:
        """Flushes, renames the file into place and returns its path."""
        if self._file.closed:  # closed before (a second close, or after discard)
            return self._written
        try:
            try:
                self._file.close()
                self._written = self._out.commit()
            except OSError as exc:
                raise OutputError(self.path, reason_of(exc)) from None
            return self._written
        finally:
            self._out.discard()

    def discard(self) -> None:
        """Drops the log (an interrupted run): nothing is left under the path, nor a temporary file."""
        try:
            self._file.close()
        finally:
            self._out.discard()
