"""Error classes with the CLI's messages, and the GIL released during a map."""

import numpy as np
import pytest

import conformap
from conftest import assert_gil_released, FIXTURES, run_cli


def test_error_classes():
    assert issubclass(conformap.ConformapError, ValueError)
    assert issubclass(conformap.NumericalError, RuntimeError)


def test_bad_arrays_raise_conformap_error():
    V, F = conformap.read_mesh(FIXTURES / "woody.obj")
    with pytest.raises(conformap.ConformapError, match="face 0: vertex index"):
        bad = F.copy()
        bad[0, 1] = V.shape[0]
        conformap.disk_map(V, bad)
    with pytest.raises(conformap.ConformapError, match="F must be an integer array"):
        conformap.disk_map(V, F.astype(np.float64))
    with pytest.raises(conformap.ConformapError, match=r"V must have shape \(n, 3\)"):
        conformap.disk_map(V[:, :2], F)
    with pytest.raises(conformap.ConformapError, match="method must be one of"):
        conformap.disk_map(V, F, method="nope")


def test_wrong_topology_has_the_cli_message(tmp_path):
    # a closed mesh asked for a disk map: the CLI's message, with <arrays> for the path
    V, F = conformap.read_mesh(FIXTURES / "spot.obj")
    with pytest.raises(conformap.ConformapError) as info:
        conformap.disk_map(V, F)
    code, _, err = run_cli(["disk", str(FIXTURES / "spot.obj"), "-o", str(tmp_path / "o.obj")], tmp_path)
    assert code == 1
    cli_line = err.splitlines()[0].removeprefix("error: ")
    cli_message = cli_line.split(": ", 1)[1]  # drop the path
    py_message = str(info.value).splitlines()[0].split(": ", 1)[1]
    assert py_message == cli_message


def test_numerical_failure_raises_runtime_error():
    # strict refuses a map that did not converge, as --strict does (exit 3)
    V, F = conformap.read_mesh(FIXTURES / "woody.obj")
    with pytest.raises(conformap.NumericalError, match="strict"):
        conformap.disk_map(V, F, max_iter=1, strict=True)


def test_gil_released_during_map():
    V, F = conformap.read_mesh(FIXTURES / "spothead.obj")
    assert_gil_released(lambda: conformap.disk_map(V, F))
