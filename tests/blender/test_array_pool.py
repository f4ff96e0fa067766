"""The export's array pool (array_pool.py): an array comes back only once nothing else refers to
it, a second export reuses the first one's memory once its dict is gone and exports the same
numbers, and the pool keeps to its bound."""

import threading

import bpy
import numpy as np

from bxdf_lab import array_pool, export


def _address(a):
    return a.__array_interface__["data"][0]


def test_an_array_comes_back_only_when_nothing_else_refers_to_it():
    pool = array_pool.ArrayPool()
    pool.begin_export()
    a = pool.empty(1000, np.float32)
    address = _address(a)
    view = a.reshape(500, 2)
    del a
    b = pool.empty(1000, np.float32)  # the first is still seen through its view
    assert _address(b) != address
    del view, b
    c = pool.empty(1000, np.float32)  # both free now: the first kept comes back
    assert _address(c) == address
    assert pool.empty(1000, np.int32).dtype == np.int32  # another dtype, another array
    zeros = pool.zeros(10, np.int32)
    assert not zeros.any()


def test_the_pool_keeps_what_the_last_two_exports_used_and_its_bound():
    pool = array_pool.ArrayPool(max_bytes=4000)
    pool.begin_export()
    pool.empty(500, np.float32)  # 2000 bytes, kept
    pool.empty(500, np.float64)  # 4000 more: past the bound, not kept
    assert pool.nbytes == 2000
    pool.begin_export()
    assert pool.nbytes == 2000  # the last export's arrays stay
    pool.begin_export()
    assert pool.nbytes == 0  # unused in two exports: let go


def test_exports_at_once_never_get_the_same_array():
    pool = array_pool.ArrayPool()
    pool.begin_export()
    for _ in range(8):  # kept arrays, all free again
        pool.empty(64, np.float32)
    held = {0: [], 1: []}

    def claim(k):
        for _ in range(200):
            held[k].append(pool.empty(64, np.float32))

    threads = [threading.Thread(target=claim, args=(k,)) for k in held]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    addresses = [_address(a) for k in held for a in held[k]]
    assert len(set(addresses)) == len(addresses)


def _scene():
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32)
    bpy.ops.mesh.primitive_cube_add(location=(3, 0, 0))
    bpy.context.active_object.data.uv_layers.new(name="UVMap")
    bpy.ops.object.shade_smooth()
    return bpy.context.evaluated_depsgraph_get()


def _arrays(data):
    return [m[k] for m in data["meshes"] for k in
            ("positions", "triangles", "normals", "normal_indices", "uvs", "uv_indices",
             "material_indices") if m.get(k) is not None]


def test_a_second_export_reuses_the_first_ones_memory_with_the_same_numbers():
    depsgraph = _scene()
    first = export.export_scene(depsgraph)
    expected = [a.copy() for a in _arrays(first)]
    held = export.export_scene(depsgraph)  # while `first` is alive: memory of its own
    first_addresses = {_address(a) for a in _arrays(first)}
    assert not first_addresses & {_address(a) for a in _arrays(held)}
    for a, b in zip(_arrays(held), expected):
        np.testing.assert_array_equal(a, b)
    del first
    again = export.export_scene(depsgraph)
    assert first_addresses & {_address(a) for a in _arrays(again)}  # reused
    for a, b in zip(_arrays(again), expected):
        np.testing.assert_array_equal(a, b)
    for a, b in zip(_arrays(held), expected):  # not written over
        np.testing.assert_array_equal(a, b)
