"""Shared fixtures: the repository's fixture meshes and the CLI binary to compare with."""
import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]
FIXTURES = ROOT / "fixtures"


def cli_binary() -> pathlib.Path:
    """The `conformap` binary: $CONFORMAP_BIN, else target/debug (built by `cargo test`)."""
    path = pathlib.Path(os.environ.get("CONFORMAP_BIN", ROOT / "target" / "debug" / "conformap"))
    if not path.exists():
        pytest.fail(f"no CLI binary at {path}: run `cargo build -p conformap-cli` first")
    return path


def run_cli(args, tmp_path):
    """Runs the CLI with `--report`; returns (returncode, report dict or None, stderr)."""
    report = tmp_path / "report.json"
    proc = subprocess.run(
        [str(cli_binary()), *args, "--report", str(report)],
        capture_output=True,
        text=True,
        check=False,
    )
    data = json.loads(report.read_text()) if proc.returncode == 0 else None
    return proc.returncode, data, proc.stderr


@pytest.fixture
def fixture_path():
    return lambda name: FIXTURES / name
