"""Paths for the tests: the source tree (models, CAD files) and the build tree (the iga app).
CTest sets IGA_SOURCE_DIR and IGA_BUILD_DIR; run by hand, the defaults are this checkout and
its build/release."""
import os
import pathlib

import pytest

SOURCE = pathlib.Path(os.environ.get("IGA_SOURCE_DIR",
                                     pathlib.Path(__file__).resolve().parents[2]))
BUILD = pathlib.Path(os.environ.get("IGA_BUILD_DIR", SOURCE / "build" / "release"))


@pytest.fixture
def source():
    return SOURCE


@pytest.fixture
def build():
    return BUILD
