"""Shared helpers of the Python tests: the `ltp` command of this build as the reference.

ctest runs these with PYTHONPATH=<build>/python and LTP_BINARY=<build>/cli/ltp (see
tests/CMakeLists.txt); by hand:
    PYTHONPATH=build/python LTP_BINARY=build/cli/ltp /usr/bin/python3 -m pytest tests/python
"""
import json
import math
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def ltp_cli():
    """Runs `ltp ARGS --json` and returns the parsed JSON (exit 0 or 1: the result is there)."""
    binary = os.environ.get("LTP_BINARY")
    if not binary or not os.access(binary, os.X_OK):
        pytest.fail("LTP_BINARY must name the built ltp executable")

    def run(*args):
        done = subprocess.run([binary, *args, "--json"], capture_output=True, text=True, check=False)
        assert done.returncode in (0, 1), f"ltp {' '.join(args)}: exit {done.returncode}: {done.stderr}"
        return json.loads(done.stdout)

    return run


def number(value):
    """A JSON number of `ltp --json` (non-finite ones are written as strings)."""
    return float(value) if isinstance(value, str) else value


def same(a, b):
    """Equal to the last bit (NaN equals NaN)."""
    a, b = number(a), number(b)
    if isinstance(a, float) and math.isnan(a):
        return isinstance(b, float) and math.isnan(b)
    return a == b
