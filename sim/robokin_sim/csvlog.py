"""The CSV log: one row per simulation step with the columns of DESIGN.md.

Floats are written with ``repr`` (shortest round-trip form), so a test reading the log sees the
exact values the simulator had. The file is written under a temporary name and renamed when closed.
"""

from __future__ import annotations

import csv
from typing import Optional, Sequence

from robokin._atomic import AtomicPath


class CsvLog:
    """Writes rows under a header.

    Args:
        path: The CSV file to write.
        columns: The header.
    """

    def __init__(self, path: str, columns: Sequence[str]) -> None:
        self.path = path
        self.columns = tuple(columns)
        self.rows = 0
        self._out = AtomicPath(path)
        self._written: Optional[str] = None
        self._file = open(self._out.tmp, "w", newline="", encoding="utf-8")
        self._writer = csv.writer(self._file, lineterminator="\n")
        self._writer.writerow(self.columns)

    def write(self, row: Sequence) -> None:
        """Appends one row (as many values as columns)."""
        self._writer.writerow(row)
        self.rows += 1

    def close(self) -> Optional[str]:
        """Flushes, renames the file into place and returns its path."""
        if self._file.closed:  # closed before (a second close, or after discard)
            return self._written
        try:
            self._file.close()
            self._written = self._out.commit()
            return self._written
        finally:
            self._out.discard()

    def discard(self) -> None:
        """Drops the log (an interrupted run): nothing is left under the path, nor a temporary file."""
        try:
            self._file.close()
        finally:
            self._out.discard()
