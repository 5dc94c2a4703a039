"""Shared fixtures: the host-sim CLI (to make preset scenarios and the CLI's own estimates to compare with).

The CLI is ``$RFISST_HOST_SIM`` when set (CI sets it to the release binary it built), else
``cargo run --release -p host-sim`` from the repository this package sits in.
"""

from __future__ import annotations

import csv
import json
import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def _host_sim_command() -> list[str]:
    explicit = os.environ.get("RFISST_HOST_SIM")
    if explicit:
        return [explicit]
    return ["cargo", "run", "--quiet", "--release", "--manifest-path", str(REPO / "Cargo.toml"), "-p", "host-sim", "--"]


class HostSim:
    """Runs host-sim, caching each preset's scenario and run under one temporary folder."""

    def __init__(self, root: Path) -> None:
        self.root = root
        self.command = _host_sim_command()

    def __call__(self, *args: str) -> None:
        subprocess.run([*self.command, *args], check=True, stdout=subprocess.DEVNULL)

    def scenario(self, preset: str) -> Path:
        path = self.root / f"{preset}.json"
        if not path.exists():
            self("generate", preset, "--seed", "1", "--out", str(path))
        return path

    def estimates(self, preset: str) -> list[dict[str, str]]:
        """The rows of ``host-sim run``'s estimates.csv for the preset (default tracker and profile)."""
        out = self.root / f"run-{preset}"
        if not (out / "estimates.csv").exists():
            self("run", str(self.scenario(preset)), "--out", str(out))
        with open(out / "estimates.csv", newline="") as f:
            return list(csv.DictReader(f))


@pytest.fixture(scope="session")
def host_sim(tmp_path_factory: pytest.TempPathFactory) -> HostSim:
    return HostSim(tmp_path_factory.mktemp("host-sim"))


def load(path: Path) -> dict:
    with open(path) as f:
        return json.load(f)
