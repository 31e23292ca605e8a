"""The CSV log: one row per simulation step with the columns of DESIGN.md.

Floats are written with ``repr`` (shortest round-trip form), so a test reading the log sees the
exact values the simulator had. The file is written under a temporary name and renamed when closed.
"""

from __future__ import annotations

import csv
import os
from typing import Optional, Sequence

from .recording import _temporary_path


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
        self._tmp = _temporary_path(path)
        self._file = open(self._tmp, "w", newline="", encoding="utf-8")
        self._writer = csv.writer(self._file, lineterminator="\n")
        self._writer.writerow(self.columns)

    def write(self, row: Sequence) -> None:
        """Appends one row (as many values as columns)."""
        self._writer.writerow(row)
        self.rows += 1

    def close(self) -> Optional[str]:
        """Flushes, renames the file into place and returns its path."""
        if self._file.closed:
            return self.path
        self._file.close()
        os.replace(self._tmp, self.path)
        return self.path
