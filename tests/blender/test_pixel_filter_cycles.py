"""BXDF_LAB's pixel filters against Cycles': the profile across a sharp emissive edge, seen by an
orthographic camera, is the filter's CDF. With both engines at their defaults (Blackman-Harris,
1.5 px) the profiles agree within noise; Cycles' Gaussian gives a measurably different one, so
the test would see a wrong filter."""

import bpy
import numpy as np

import pairing_scene

WIDTH, HEIGHT, SAMPLES = 16, 16, 4096


def _edge_scene():
    scene = bpy.context.scene
    # An emissive plane whose edge crosses the view at 0.3 px right of a pixel boundary.
    bpy.ops.mesh.primitive_plane_add(size=20.0, location=(-10.0 + 0.3 * 4.0 / WIDTH, 0.0, 0.0))
    plane = bpy.context.active_object
    material = bpy.data.materials.new("edge")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    material.node_tree.links.new(emission.outputs["Emission"],
                                 nodes["Material Output"].inputs["Surface"])
    plane.data.materials.append(material)
    # Looking down -Z, 4 units over 16 px: 0.25 per pixel.
    pairing_scene.add_camera(scene, (0.0, 0.0, 5.0), ortho_scale=4.0)
    pairing_scene.uniform_world(scene)
    pairing_scene.exr_output(scene, WIDTH, HEIGHT)
    scene.bxdf_lab_render.samples, scene.bxdf_lab_render.max_bounces = SAMPLES, 0
    c = scene.cycles
    c.samples, c.max_bounces, c.use_denoising, c.use_adaptive_sampling = SAMPLES, 0, False, False
    return scene


def _profile(scene, engine_id, path):
    """Mean over rows of each column, and its standard error."""
    red = pairing_scene.render_rgba(scene, engine_id, path)[..., 0].astype(np.float64)
    mean = red.mean(axis=0)
    # Each sample is 0 or 1: the binomial error of the column's mean over rows × samples.
    error = np.sqrt(np.clip(mean * (1 - mean), 0, None) / (HEIGHT * SAMPLES)) + 1e-4
    return mean, error


def _z(a, b):
    return np.abs(a[0] - b[0]) / np.hypot(a[1], b[1])


def test_default_filter_is_cycles_blackman_harris(tmp_path):
    scene = _edge_scene()
    assert scene.cycles.pixel_filter_type == "BLACKMAN_HARRIS"
    assert scene.bxdf_lab_render.pixel_filter == "BLACKMAN_HARRIS"
    assert scene.bxdf_lab_render.filter_width == scene.cycles.filter_width == 1.5
    ours = _profile(scene, "BXDF_LAB", tmp_path / "ours_bh.exr")
    cycles = _profile(scene, "CYCLES", tmp_path / "cycles_bh.exr")
    # The edge is seen: bright on the left, dark on the right, a ramp between.
    assert cycles[0][0] > 0.99 and cycles[0][-1] < 0.01
    assert _z(ours, cycles).max() < 4.5, (ours[0], cycles[0])

    scene.cycles.pixel_filter_type = "GAUSSIAN"
    cycles_gauss = _profile(scene, "CYCLES", tmp_path / "cycles_gauss.exr")
    # The test can tell the two filters apart.
    assert _z(ours, cycles_gauss).max() > 6.0, (ours[0], cycles_gauss[0])
    scene.bxdf_lab_render.pixel_filter = "GAUSSIAN"
    ours_gauss = _profile(scene, "BXDF_LAB", tmp_path / "ours_gauss.exr")
    assert _z(ours_gauss, cycles_gauss).max() < 4.5, (ours_gauss[0], cycles_gauss[0])
