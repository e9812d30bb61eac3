import os
import pathlib
import shutil

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def shared_data():
    """../shared/data beside the repository (or $BATCHCCD_SHARED_DATA); skips when absent."""
    path = pathlib.Path(os.environ.get("BATCHCCD_SHARED_DATA", REPO.parent / "shared" / "data"))
    if not (path / "scenes").is_dir():
        pytest.skip(f"no shared data at {path}")
    return path


@pytest.fixture(scope="session")
def cli():
    """The batchccd command-line tool: $BATCHCCD_CLI (ctest sets it to the tool built beside the
    module), else the one on PATH. Never a build directory's by guess: it may be older than the module."""
    named = os.environ.get("BATCHCCD_CLI")
    if named:
        if not pathlib.Path(named).is_file():
            pytest.fail(f"BATCHCCD_CLI={named} is not a file")
        return named
    on_path = shutil.which("batchccd")
    if on_path is None:
        pytest.skip("no batchccd tool: set BATCHCCD_CLI or put it on PATH")
    return on_path
