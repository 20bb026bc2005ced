"""Shared fixtures of the Python module's tests: the bundled meshes and the limsurf CLI, whose
--json output is the yardstick every binding must reproduce exactly.

ctest sets PYTHONPATH to the build tree's python/ folder, LIMSURF_CLI to the command-line tool and
LIMSURF_MESH_DIR to data/meshes (tests/python/CMakeLists.txt)."""
import json
import os
import pathlib
import subprocess

import pytest

MESH_DIR = pathlib.Path(os.environ.get("LIMSURF_MESH_DIR", pathlib.Path(__file__).resolve().parents[2] / "data" / "meshes"))


@pytest.fixture(scope="session")
def mesh_path():
    """mesh_path("cube") -> path of data/meshes/cube.obj (as a string)."""

    def path(name):
        p = MESH_DIR / (name if "." in name else name + ".obj")
        assert p.exists(), p
        return str(p)

    return path


def _tool():
    tool = os.environ.get("LIMSURF_CLI")
    if not tool:
        pytest.skip("LIMSURF_CLI is not set (ctest sets it): the CLI comparisons need the limsurf tool")
    return tool


@pytest.fixture(scope="session")
def cli_tool():
    """cli_tool(args...): runs the limsurf command (it must exit 0) and returns its stdout."""

    def run(*args):
        done = subprocess.run([_tool(), *map(str, args)], capture_output=True, text=True, timeout=300)
        assert done.returncode == 0, done.stderr
        return done.stdout

    return run


@pytest.fixture(scope="session")
def cli():
    """cli(args...) -> the parsed JSON the limsurf command prints (it must exit 0)."""
    def run(*args):
        done = subprocess.run([_tool(), *map(str, args)], capture_output=True, text=True, timeout=300)
        assert done.returncode == 0, done.stderr
        return json.loads(done.stdout)

    return run
