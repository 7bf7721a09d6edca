"""The warplab binary for the tests that make real sessions and exports.

ctest passes it as WARPLAB_BINARY (tests/CMakeLists.txt). Run by hand, the tests look for
build/app/warplab and are skipped, saying so, when there is none.
"""
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def binary():
    path = os.environ.get("WARPLAB_BINARY") or str(ROOT / "build" / "app" / "warplab")
    if not os.path.exists(path):
        if os.environ.get("WARPLAB_BINARY"):
            pytest.fail(f"WARPLAB_BINARY={path} does not exist")
        pytest.skip("no warplab binary (build it, or set WARPLAB_BINARY)")
    return path


def run(*args, cwd=None):
    done = subprocess.run(list(map(str, args)), capture_output=True, text=True, timeout=300, cwd=cwd)
    assert done.returncode == 0, f"{args}: {done.stderr}"
    return done
