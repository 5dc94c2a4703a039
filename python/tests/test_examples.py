"""The README's Python example (python/examples/stonesoup_quickstart.py) runs as a user would run it."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "stonesoup_quickstart.py"


def test_the_stone_soup_quickstart_runs_and_tracks() -> None:
    done = subprocess.run([sys.executable, str(EXAMPLE)], check=True, capture_output=True, text=True)
    last = done.stdout.strip().splitlines()[-1].split()
    assert last[0] == "scans" and int(last[1]) == 40, done.stdout
    assert last[2] == "tracks" and int(last[3]) > 0, done.stdout


def test_the_readme_shows_the_example_as_it_is() -> None:
    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    body = EXAMPLE.read_text()
    assert body[body.index("import datetime") :].rstrip("\n") in readme
