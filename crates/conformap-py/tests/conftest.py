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


def cli_error(args, tmp_path):
    """Runs the CLI expecting a failure; returns (returncode, its message without the
    path in front, its hint line or None)."""
    code, _, err = run_cli(args, tmp_path)
    lines = err.splitlines()
    message = lines[0].removeprefix("error: ")
    hint = next((l.removeprefix("hint: ") for l in lines[1:] if l.startswith("hint: ")), None)
    return code, message, hint


def after_place(message, place):
    """The message after `place: ` (a file of the CLI, a `<...>` name of the package)."""
    prefix = f"{place}: "
    assert message.startswith(prefix), (message, prefix)
    return message[len(prefix):]


def torus(n=24, m=12, R=2.0, r=0.7):
    """A torus of revolution (genus 1, closed): (V, F), consistently oriented."""
    import numpy as np

    u, v = np.meshgrid(np.arange(n) * 2 * np.pi / n, np.arange(m) * 2 * np.pi / m, indexing="ij")
    V = np.stack([(R + r * np.cos(v)) * np.cos(u), (R + r * np.cos(v)) * np.sin(u), r * np.sin(v)], -1)
    idx = lambda i, j: (i % n) * m + (j % m)
    F = []
    for i in range(n):
        for j in range(m):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            F += [[a, b, c], [a, c, d]]
    return V.reshape(-1, 3), np.array(F, dtype=np.int64)


def assert_gil_released(call):
    """Runs `call()` while a Python thread ticks about once a millisecond, and asserts that
    the thread kept running: with the GIL held it could not run at all during the call;
    released, it ticks about once a millisecond (a loaded machine is allowed a factor of 20)."""
    import threading
    import time

    ticks = 0
    stop = threading.Event()

    def count():
        nonlocal ticks
        while not stop.is_set():
            ticks += 1
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    time.sleep(0.05)
    start = ticks
    t0 = time.perf_counter()
    call()
    elapsed = time.perf_counter() - t0
    during = ticks - start
    stop.set()
    t.join()
    assert elapsed > 0.05
    assert during > elapsed * 1000 / 20, (during, elapsed)
