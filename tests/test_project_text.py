"""What the project says to its readers: the user README stays user documentation, and no file
names the tracker's issue numbers or the course texts by their file numbers (the README names the
studies once, by subject)."""

import pathlib
import re
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
README = ROOT / "README.md"


def _tracked_text_files():
    try:
        out = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("not a git checkout: the tracked files cannot be listed")
    for name in out.decode().split("\0"):
        path = ROOT / name
        if name and path.is_file() and path.suffix not in {".png", ".gif", ".mp4", ".whl"}:
            try:
                yield name, path.read_text(encoding="utf-8")
            except UnicodeDecodeError:
                continue


@pytest.mark.parametrize("pattern, what", [
    (r"\b[Ii]ssues?\s+#?\d+", "an issue number"),
    (r"\bseed[-\s]+0\d\d\b", "a course text by its file number"),
])
def test_no_file_names_issue_numbers_or_seed_files(pattern, what):
    me = pathlib.Path(__file__).name
    # The whole text is searched, so a name broken across two lines is found too.
    hits = [f"{name}:{text.count(chr(10), 0, m.start()) + 1}: {' '.join(m.group().split())}"
            for name, text in _tracked_text_files() if not name.endswith(me)
            for m in re.finditer(pattern, text)]
    assert not hits, f"{len(hits)} line(s) name {what}:\n" + "\n".join(hits[:20])


def test_the_readme_is_user_documentation():
    text = README.read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 300
    # History and measurements live in benchmarks/README.md: no dates, no profiler talk.
    for pattern in (r"\b20\d\d-\d\d-\d\d\b", r"callgrind", r"MADV_FREE", r"[Mm]easured and dropped"):
        assert not re.search(pattern, text), pattern
    assert "benchmarks/README.md" in text
    for command in ("make run", "make test", "make wheel", ".venv/bin/robokin-sim", "source .venv/bin/activate"):
        assert command in text, command
