"""Hostile files and calls (issue 15): every bad input is a ValueError with a readable message,
and errors that are not about the input (KeyboardInterrupt) pass through untouched."""

import os
import shutil
import threading
import time

import numpy as np
import pytest

import bxdf

DATA = os.path.join(os.path.dirname(__file__), "..", "..", "data", "measured")


def write(tmp_path, name, data):
    p = tmp_path / name
    p.write_bytes(data if isinstance(data, bytes) else data.encode())
    return p


def test_deeply_nested_material_file_is_a_value_error(tmp_path):
    # 100,000 nested arrays once overflowed the stack and took the interpreter down.
    p = write(tmp_path, "deep.json", '{"model": "lambertian", "params": ' + "[" * 100000 + "]" * 100000 + "}")
    with pytest.raises(ValueError, match=r"deep\.json: nesting deeper than 256"):
        bxdf.load_material(p)


def test_number_past_double_range_is_a_value_error_naming_the_file(tmp_path):
    p = write(tmp_path, "huge.json", '{"model": "lambertian", "params": {"reflectance": 1e999}}')
    with pytest.raises(ValueError, match=r"huge\.json: not valid JSON: .*number overflow"):
        bxdf.load_material(p)


def test_bytes_that_are_not_utf8_are_escaped_in_the_message(tmp_path):
    p = write(tmp_path, "bytes.json", b'{"model": "lamb\xff\xfe"}')
    with pytest.raises(ValueError) as info:
        bxdf.load_material(p)
    assert "bytes.json" in str(info.value) and "\\xff" in str(info.value)
    cornell = write(tmp_path, "bytes.brdf", b"# num wls\n31\n# wls\n\xff\n")
    with pytest.raises(ValueError, match=r"'\\xff' is not a number"):
        bxdf.load_measured(cornell)


@pytest.mark.parametrize("text,message", [
    ('{"format": "bxdf-material", "version": 4294967297, "model": "lambertian"}', "field 'version'"),
    ('{"model": "lambertian", "model": "lambertian"}', 'duplicate key "model"'),
    ('{"model": "measured", "params": {"path": "/nonexistent/paint.brdf"}}', r"m\.json: .*/nonexistent/paint\.brdf"),
])
def test_bad_material_files(tmp_path, text, message):
    with pytest.raises(ValueError, match=message):
        bxdf.load_material(write(tmp_path, "m.json", text))


def test_devices_are_not_read_as_files():
    for call in (bxdf.load_material, bxdf.load_measured):
        with pytest.raises(ValueError, match="not a regular file"):
            call("/dev/zero")
    if hasattr(bxdf, "render_scene_file"):
        with pytest.raises(ValueError, match="not a regular file"):
            bxdf.render_scene_file("/dev/zero")


def test_paths_with_nul_are_refused(tmp_path):
    calls = [bxdf.load_material, bxdf.load_measured, lambda p: bxdf.save_material(bxdf.make("lambertian"), p)]
    if hasattr(bxdf, "render_scene_file"):
        calls.append(bxdf.render_scene_file)
    for call in calls:
        with pytest.raises(ValueError, match="NUL"):
            call(str(tmp_path / "a\0b.json"))
    with pytest.raises(ValueError, match="NUL"):
        bxdf.make("measured", path=os.path.join(DATA, "acryl_blue.brdf") + "\0x")


def test_parameter_too_large_for_a_float_names_the_parameter():
    with pytest.raises(ValueError, match="reflectance"):
        bxdf.make("lambertian", reflectance=10**400)
    with pytest.raises(ValueError, match="reflectance"):
        bxdf.make("lambertian", reflectance=(0.5, 10**400, 0.5))


def test_masked_arrays_are_refused():
    m = bxdf.make("lambertian")
    wo = np.ma.masked_array([[0.0, 0.0, 1.0]], mask=[[False, False, True]])
    with pytest.raises(ValueError, match="masked array"):
        m.f(wo, np.array([[0.0, 0.0, 1.0]]))


class Interrupting:
    """A value whose conversion is interrupted (as by Ctrl-C at that moment)."""

    error = KeyboardInterrupt

    def __index__(self):
        raise self.error

    def __float__(self):
        raise self.error

    def __array__(self, dtype=None):
        raise self.error


class OutOfMemory(Interrupting):
    """A value whose conversion runs out of memory."""

    error = MemoryError


# Errors that are not about the value pass through the conversion untouched.
not_about_the_value = pytest.mark.parametrize("failing", [Interrupting, OutOfMemory])


@not_about_the_value
def test_interrupt_or_memory_error_during_argument_conversion_propagates(failing):
    m = bxdf.make("lambertian")
    with pytest.raises(failing.error):
        m.rho_hh(failing())
    with pytest.raises(failing.error):
        m.f(failing(), np.array([0.0, 0.0, 1.0]))


render_only = pytest.mark.skipif(not hasattr(bxdf, "render"), reason="built without the renderer")


def small_scene():
    return {
        "meshes": [{"name": "quad", "positions": np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], np.float32),
                    "triangles": np.array([[0, 1, 2], [0, 2, 3]], np.int32),
                    "material_indices": np.zeros(2, np.int32)}],
        "materials": [{"name": "m", "model": "lambertian", "params": {}}],
        "lights": [],
        "camera": {"matrix": np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 3], [0, 0, 0, 1]], np.float32),
                   "lens": 50.0, "sensor_width": 36.0},
        "world": {"color": [0.5, 0.5, 0.5]},
        "resolution": (8, 8),
        "warnings": [],
    }


@render_only
def test_small_scene_renders():
    assert bxdf.render(small_scene(), {"samples": 1}).shape == (8, 8, 4)


@render_only
@not_about_the_value
def test_interrupt_or_memory_error_during_scene_conversion_propagates(failing):
    scene = small_scene()
    scene["meshes"][0]["positions"] = failing()
    with pytest.raises(failing.error):
        bxdf.render(scene, {"samples": 1})
    with pytest.raises(failing.error):
        bxdf.render(small_scene(), {"samples": failing()})


@render_only
def test_masked_scene_arrays_are_refused():
    scene = small_scene()
    p = scene["meshes"][0]["positions"]
    scene["meshes"][0]["positions"] = np.ma.masked_array(p, mask=np.zeros_like(p, bool))
    with pytest.raises(ValueError, match=r"(?s)scene\['meshes'\]\[0\]\['positions'\].*masked array"):
        bxdf.render(scene, {"samples": 1})


@render_only
@pytest.mark.parametrize("edit,message", [
    (lambda m: m.__setitem__((slice(None), 0), 0.0), r"scene\['camera'\]: camera matrix has a zero axis"),
    (lambda m: m.__setitem__((0, 3), 1e18), r"scene\['camera'\]: camera matrix\[0\]\[3\] .*\[-1e9, 1e9\]"),
    (lambda m: m.__setitem__((1, 3), -9.2e18), r"scene\['camera'\]: camera matrix\[1\]\[3\]"),
])
def test_bad_camera_matrix_names_the_field(edit, message):
    scene = small_scene()
    edit(scene["camera"]["matrix"])
    with pytest.raises(ValueError, match=message):
        bxdf.render(scene, {"samples": 1})


def test_load_measured_lets_other_threads_run(tmp_path):
    # A fresh copy, so that the cache does not answer; the Cornell table takes a while to build.
    p = tmp_path / "paint.brdf"
    shutil.copy(os.path.join(DATA, "krylon_blue.brdf"), p)
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=tick)
    t.start()
    try:
        time.sleep(0.02)
        start = time.perf_counter()
        bxdf.load_measured(p)
        end = time.perf_counter()
    finally:
        stop.set()
        t.join()
    during = [x for x in ticks if start < x < end]
    # With the GIL held for the whole read, no tick would land inside it.
    assert end - start > 0.02, "the load was too fast to tell"
    assert len(during) >= 5, (len(during), end - start)
