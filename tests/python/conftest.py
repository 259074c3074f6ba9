"""pytest set-up for the Python module's tests (ctest runs them with
PYTHONPATH=build/python, IPSTEP_SOURCE_DIR and IPSTEP_COMPARE set)."""
import os

import pytest


@pytest.fixture
def source_dir():
    return os.environ.get("IPSTEP_SOURCE_DIR",
                          os.path.join(os.path.dirname(__file__), "..", ".."))
