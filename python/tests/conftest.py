"""Shared fixtures of the binding tests: where the tools and the datasets are, and running a tool.

ctest (python/CMakeLists.txt) sets PYTHONPATH to build/python and VSTCAL_TOOLS_DIR to build/tools;
by hand: PYTHONPATH=build/python VSTCAL_TOOLS_DIR=build/tools /usr/bin/python3 -m pytest python/tests
"""
import json
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("VSTCAL_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
TOOLS_DIR = pathlib.Path(os.environ.get("VSTCAL_TOOLS_DIR", SOURCE_DIR / "build" / "tools"))
DATASETS = SOURCE_DIR / "datasets"
OPENCV_DATA = pathlib.Path("/usr/share/doc/opencv-doc/examples/data")


def run_tool(tool, *args, expect=0, cwd=None):
    """Runs build/tools/<tool> with the arguments; checks its exit code and returns the CompletedProcess."""
    p = subprocess.run([str(TOOLS_DIR / tool), *map(str, args)], capture_output=True, text=True, cwd=cwd)
    assert p.returncode == expect, f"{tool} {' '.join(map(str, args))}: exit {p.returncode}\n{p.stderr}"
    return p


def tool_error(tool, *args, code=2):
    """The one-line message a tool prints for an error (without its 'tool: error: ' prefix)."""
    p = run_tool(tool, *args, expect=code)
    line = p.stderr.strip().splitlines()[0]
    prefix = f"{tool}: error: "
    assert line.startswith(prefix), line
    return line[len(prefix):]


def load(path):
    with open(path) as f:
        return json.load(f)


def without_provenance(document):
    return {k: v for k, v in document.items() if k != "provenance"}


@pytest.fixture(scope="session")
def vstcal():
    import vstcal as module
    return module


def assert_documents_close(a, b, rel=1e-9, path="document"):
    """Two JSON documents with the same keys, lists and strings, and numbers equal to `rel`."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and list(a) == list(b), f"{path}: keys {list(a)} != {list(b)}"
        for k in a:
            assert_documents_close(a[k], b[k], rel, f"{path}.{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), f"{path}: lengths differ"
        for i, (x, y) in enumerate(zip(a, b)):
            assert_documents_close(x, y, rel, f"{path}[{i}]")
    elif isinstance(a, float) or isinstance(b, float):
        assert abs(a - b) <= rel * max(abs(a), abs(b), 1e-300) or a == b, f"{path}: {a} != {b}"
    else:
        assert a == b, f"{path}: {a!r} != {b!r}"
