"""Shared fixtures of the Blender tests: the add-on enabled once, an empty file per test."""

import addon_utils
import bpy
import pytest


@pytest.fixture(scope="session", autouse=True)
def addon():
    module = addon_utils.enable("bxdf_lab", default_set=True, handle_error=None)
    assert module is not None, "bxdf_lab did not enable"
    yield module
    addon_utils.disable("bxdf_lab", default_set=True)


@pytest.fixture
def bxdf():
    from bxdf_lab import dependency
    module = dependency.try_import()
    assert module is not None, dependency.help_text()
    return module


@pytest.fixture(autouse=True)
def empty_file():
    bpy.ops.wm.read_homefile(use_empty=True)
    yield


@pytest.fixture
def material():
    return bpy.data.materials.new("Test Material")
