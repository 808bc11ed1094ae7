"""Shared fixtures: the CLI the package is compared with, run as a process."""

from __future__ import annotations

import json
import os
import pathlib
import subprocess
from typing import List

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
# The shared folder beside the clone (a worktree elsewhere: STICKSLIP_SHARED).
SHARED = pathlib.Path(os.environ.get("STICKSLIP_SHARED", str(REPO.parent / "shared")))


class Cli:
    """The `stickslip` binary: `STICKSLIP_CLI`, else the repo's release build."""

    def __init__(self) -> None:
        path = os.environ.get("STICKSLIP_CLI", str(REPO / "target" / "release" / "stickslip"))
        if not pathlib.Path(path).is_file():
            pytest.fail(f"no CLI at {path}: run `cargo build --release` or set STICKSLIP_CLI")
        self.path = path

    def run(self, *args: str) -> subprocess.CompletedProcess:
        return subprocess.run([self.path, *args], capture_output=True, text=True, timeout=600)

    def json(self, *args: str) -> dict:
        out = self.run(*args, "--json")
        assert out.returncode == 0, out.stderr
        return json.loads(out.stdout)

    def error(self, *args: str) -> str:
        """The message of a failing command (`error: MSG` on stderr)."""
        out = self.run(*args)
        assert out.returncode != 0
        lines: List[str] = [l for l in out.stderr.splitlines() if l.startswith("error: ")]
        assert len(lines) == 1, out.stderr
        return lines[0][len("error: ") :]


@pytest.fixture(scope="session")
def cli() -> Cli:
    return Cli()


def close(a, b, tol: float = 1e-12, path: str = "") -> None:
    """`a` and `b` (JSON values) agree: numbers to `tol` relative, the rest exactly."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and list(a) == list(b), f"{path}: keys {list(a)} vs {list(b)}"
        for k in a:
            close(a[k], b[k], tol, f"{path}.{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), f"{path}: lengths differ"
        for i, (x, y) in enumerate(zip(a, b)):
            close(x, y, tol, f"{path}[{i}]")
    elif isinstance(a, float) or isinstance(b, float):
        assert abs(a - b) <= tol * max(1.0, abs(a), abs(b)), f"{path}: {a} vs {b}"
    else:
        assert a == b, f"{path}: {a!r} vs {b!r}"
