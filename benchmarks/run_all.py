"""Runs every benchmarks/bench_*.py in turn (make bench)."""

import pathlib
import runpy

for path in sorted(pathlib.Path(__file__).parent.glob("bench_*.py")):
    print(f"== {path.name}")
    runpy.run_path(str(path), run_name="__main__")
