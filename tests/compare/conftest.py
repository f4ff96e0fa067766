"""Shared runs of the harness for the compare tests: each fixture renders once per session."""
import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from harness_helpers import MAIN_SCENES, WRONG_MATERIAL, run_compare  # noqa: E402


@pytest.fixture(scope="session")
def main_run(tmp_path_factory):
    """Six small scenes at 32x32, 8 spp, every engine, one material deliberately wrong."""
    out = tmp_path_factory.mktemp("main")
    return run_compare(out, "--scenes", *MAIN_SCENES, "--res", "32", "32", "--spp", "8",
                       "--override", WRONG_MATERIAL)
