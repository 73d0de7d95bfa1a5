"""The examples of the stubs and of the READMEs run as written (fixture paths from the
repository root): every ``Example::`` block of ``conformap.pyi`` and every ``python`` block
of the READMEs."""

import os
import pathlib
import re
import textwrap

import pytest

import conformap
from conftest import ROOT

STUBS = pathlib.Path(__file__).resolve().parents[1] / "conformap.pyi"
READMES = [ROOT / "README.md", ROOT / "crates" / "conformap-py" / "README.md"]


def stub_examples():
    """(function, code) of every ``Example::`` block of the stubs."""
    text = STUBS.read_text()
    out = []
    for m in re.finditer(r"\n( *)Example::\n\n((?:\1    .*\n|\n)+)", text):
        code = textwrap.dedent(m.group(2))
        before = text[: m.start()]
        name = re.findall(r"\ndef (\w+)", before)
        out.append((name[-1] if name else "module", code))
    return out


def readme_python_blocks():
    out = []
    for readme in READMES:
        for k, m in enumerate(re.finditer(r"```python\n(.*?)```", readme.read_text(), re.S)):
            out.append((f"{readme.relative_to(ROOT)}#{k}", m.group(1)))
    return out


@pytest.fixture
def in_tmp(tmp_path, monkeypatch):
    """Runs in a fresh directory where `fixtures/` is the repository's."""
    (tmp_path / "fixtures").symlink_to(ROOT / "fixtures")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def prelude():
    """What the examples assume: `V, F` a disk (woody), `uv` its disk map."""
    import numpy as np

    V, F = conformap.read_mesh("fixtures/woody.obj")
    uv, _ = conformap.disk_map(V, F)
    return {"conformap": conformap, "np": np, "numpy": np, "V": V, "F": F, "uv": uv}


def test_every_stub_function_has_an_example():
    names = {n for n, _ in stub_examples()}
    defs = set(re.findall(r"\ndef (\w+)", STUBS.read_text()))
    assert defs <= names | {"module"}, defs - names


@pytest.mark.parametrize("name,code", stub_examples(), ids=[n for n, _ in stub_examples()])
def test_stub_example_runs(name, code, in_tmp):
    exec(compile(code, f"conformap.pyi:{name}", "exec"), prelude())


@pytest.mark.parametrize("where,code", readme_python_blocks(), ids=[w for w, _ in readme_python_blocks()])
def test_readme_python_block_runs(where, code, in_tmp):
    exec(compile(code, where, "exec"), {})
