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
    """The batchccd command-line tool: $BATCHCCD_CLI, build/cli/batchccd, or on PATH."""
    for candidate in (os.environ.get("BATCHCCD_CLI"), REPO / "build" / "cli" / "batchccd", shutil.which("batchccd")):
        if candidate and pathlib.Path(candidate).is_file():
            return str(candidate)
    pytest.skip("no batchccd tool")
