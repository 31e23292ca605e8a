"""Files written whole or not at all: write to a temporary file next to the target, then rename it
into place (``os.replace`` is atomic within a directory). An interrupted write (an exception,
Ctrl-C) leaves neither a truncated file under the requested name nor the temporary file behind.

The temporary file is named ``.NAME.PID.RANDOM.partEXT`` (PID: the writing process). A process
killed outright (SIGKILL, a power cut) cannot remove it; the next AtomicPath for the same target
removes the temporary files of that target whose process is gone, and only those. A line-oriented
file (a CSV log streamed row by row) can be kept instead: :func:`keep_stale` renames what a dead
writer left to ``NAME.partial.EXT``, its complete lines only, before a new writer starts.

Used by robokin's figures and demos and by the simulator (recordings, CSV logs, screenshots); a
program of your own that writes results can use it the same way.
"""

from __future__ import annotations

import os
import re
import tempfile

__all__ = ["AtomicPath", "keep_stale", "remove_own", "remove_stale"]


class AtomicPath:
    """A temporary file next to ``path`` (the target; same directory and extension, so writers that look at the
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
        remove_stale(directory, stem, ext)
        fd, self.tmp = tempfile.mkstemp(prefix=f".{stem}.{os.getpid()}.", suffix=".part" + ext, dir=directory)
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


def _alive(pid: int) -> bool:
    """Whether a process with this id exists (one we may not signal exists too)."""
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _part_pattern(stem: str, pid: str, ext: str):
    """The name of a temporary file of ``STEM + EXT``: ``.STEM.PID.RANDOM.partEXT``."""
    return re.compile(r"\." + re.escape(stem) + r"\.(" + pid + r")\.[A-Za-z0-9_]+\.part" + re.escape(ext) + r"\Z")


def _parts(directory: str, pattern, dead):
    """The regular files of ``directory`` (paths, in name order) whose names match ``pattern`` and
    whose writer's PID (the pattern's group) ``dead(pid)`` says is gone."""
    try:
        names = sorted(os.listdir(directory))
    except OSError:
        return
    for name in names:
        match = pattern.match(name)
        path = os.path.join(directory, name)
        if match and dead(int(match.group(1))) and os.path.isfile(path) and not os.path.islink(path):
            yield path


def _remove_parts(directory: str, pattern, dead) -> list:
    """Removes the files :func:`_parts` lists; returns their paths."""
    removed = []
    for path in _parts(directory, pattern, dead):
        try:
            os.remove(path)
            removed.append(path)
        except OSError:
            pass
    return removed


def remove_stale(directory: str, stem: str, ext: str) -> list:
    """Removes the temporary files ``.STEM.PID.RANDOM.partEXT`` in ``directory`` whose process PID
    no longer exists (left by a killed writer of the target ``STEM + EXT``, ``stem`` and ``ext``
    its name and extension); returns their paths.
    Files of other targets, of live processes, or named otherwise are left alone."""
    return _remove_parts(directory, _part_pattern(stem, r"\d{1,10}", ext), lambda pid: not _alive(pid))


def remove_own(path) -> list:
    """Removes the temporary files this process made for ``path`` and did not commit (a run
    stopped by a signal between creating one and recording it); returns their paths."""
    path = os.fspath(path)
    directory = os.path.dirname(os.path.abspath(path))
    stem, ext = os.path.splitext(os.path.basename(path))
    return _remove_parts(directory, _part_pattern(stem, str(os.getpid()), ext), lambda pid: True)


def keep_stale(path) -> list:
    """Keeps what killed writers of ``path`` left: each temporary file ``.STEM.PID.RANDOM.partEXT``
    of a process that no longer exists is cut after its last complete line (a trailing partial
    line is dropped) and renamed to ``STEM.partialEXT`` (``STEM.partial.2EXT``, ... when taken: an
    existing file is never overwritten). Returns the paths kept. A file holding no complete line
    after its first (a header alone, or nothing) has no data and is removed. For line-oriented files
    such as CSV logs; call it before the :class:`AtomicPath` of ``path`` (which would remove them)."""
    path = os.fspath(path)
    directory = os.path.dirname(os.path.abspath(path))
    stem, ext = os.path.splitext(os.path.basename(path))
    pattern = _part_pattern(stem, r"\d{1,10}", ext)
    kept = []
    for part in _parts(directory, pattern, lambda pid: not _alive(pid)):
        # Claimed first under a name of this process: of two runs starting at once, one keeps it.
        claimed = os.path.join(directory, f".{stem}.{os.getpid()}.keep{ext}")
        try:
            os.rename(part, claimed)
        except OSError:
            continue
        kept_path = _keep_lines(claimed, os.path.join(directory, stem + ".partial"), ext)
        if kept_path is not None:
            kept.append(kept_path)
    return kept


def _keep_lines(claimed: str, base: str, ext: str):
    """Cuts ``claimed`` after its last newline and links it to the first free ``BASE[.N]EXT``
    (None, and the file removed, when it holds no line after the first)."""
    try:
        with open(claimed, "rb+") as f:
            data = f.read()
            end = data.rfind(b"\n") + 1
            if data[:end].count(b"\n") < 2:
                end = 0
            f.truncate(end)
        number = 1
        while end:
            target = base + ("" if number == 1 else f".{number}") + ext
            try:
                os.link(claimed, target)  # fails on an existing name, where a rename would overwrite
                return target
            except FileExistsError:
                number += 1
            except OSError:  # a file system without hard links: rename to a name not taken
                if os.path.lexists(target):
                    number += 1
                    continue
                os.rename(claimed, target)
                return target
    except OSError:
        pass
    finally:
        try:
            os.remove(claimed)
        except OSError:
            pass
    return None
