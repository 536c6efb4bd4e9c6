"""Where the tests find the source tree (scenes, data) and the nsbridge executable."""
import os
import pathlib

import pytest

SOURCE = pathlib.Path(os.environ.get("NSB_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BUILD = pathlib.Path(os.environ.get("NSB_BUILD_DIR", SOURCE / "build"))


@pytest.fixture
def source():
    return SOURCE


@pytest.fixture
def nsbridge_exe():
    exe = BUILD / "app" / "nsbridge"
    if not exe.exists():
        pytest.skip(f"{exe} not built")
    return exe
