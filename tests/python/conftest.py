"""Shared fixtures of the Python module's tests: the command-line renderer and the scenes."""

import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("NX_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
SCENES = SOURCE_DIR / "scenes"


def nxrender_cli():
    """The nxrender program built beside the module (ctest passes its path)."""
    path = os.environ.get("NXRENDER_CLI")
    if not path:
        raise RuntimeError("NXRENDER_CLI is not set (run these tests through ctest)")
    return path


@pytest.fixture
def run_cli(tmp_path):
    """Runs nxrender with the given arguments; returns (returncode, stderr)."""

    def run(*args):
        proc = subprocess.run([nxrender_cli(), *map(str, args)], cwd=tmp_path,
                              capture_output=True, text=True, timeout=600)
        return proc.returncode, proc.stderr

    return run


@pytest.fixture
def scenes():
    return SCENES
