"""Shared fixtures: the CLI binary the byte-equality tests run."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]


@pytest.fixture(scope="session", autouse=True)
def private_cache(tmp_path_factory):
    """Measured spectra kept by samplab.predict and the CLI go to a directory of the test
    session's, never the user's cache."""
    os.environ["SAMPLAB_CACHE"] = str(tmp_path_factory.mktemp("cache"))


@pytest.fixture(scope="session")
def cli():
    """Run the `samplab` binary (SAMPLAB_CLI, else the workspace's build) and return its
    stdout; a failing command fails the test."""
    path = os.environ.get("SAMPLAB_CLI")
    candidates = [pathlib.Path(path)] if path else [ROOT / "target" / p / "samplab" for p in ("release", "debug")]
    binary = next((c for c in candidates if c.is_file()), None)
    assert binary is not None, f"no samplab binary at {candidates}: build it (scripts/test does)"

    def run(*args):
        done = subprocess.run([str(binary), *map(str, args)], capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        return done.stdout

    return run


def load_npy(path):
    with open(path, "rb") as f:
        return np.load(f)


def pytest_configure(config):
    # scipy's engine tests (test_qmc_scipy.py) mark one case for its parallel test runner
    config.addinivalue_line("markers", "thread_unsafe: not safe to run in parallel threads (scipy's mark)")
