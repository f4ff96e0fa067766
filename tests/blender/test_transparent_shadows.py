"""Transparent shadows: a sun's light reaches a Lambertian floor through a veil the camera does
not see, and both renderers weight it by the veil's transparent part (Cycles' transparent
shadows: the Transparent BSDF's colour, times its mix weight in a mix). Every path is direct
light from a sun with no angle, so both images are noise-free and must agree to float
precision; without transparent shadows BxDF Lab's floor would be black."""

import math

import bpy
import numpy as np
import pytest

from bxdf_lab import api
from test_nodes import Tree
from test_render import _render, _scene

VEIL = (0.5, 0.8, 1.0)
FLOOR = (0.7, 0.5, 0.3)


def _assign(material, model, **params):
    """A BxDF Lab model and its exact Cycles node ("Set Up Cycles Material")."""
    api.assign(material, model, **params)
    with bpy.context.temp_override(material=material):
        assert bpy.ops.bxdf_lab.set_up_cycles() == {"FINISHED"}
    assert material.bxdf_lab.cycles_label == "exact"


def _veiled_scene(floor, veil, tmp_path):
    """test_render's floor under its sun (40° from the zenith, shining towards +y) and a veil at
    height 3.5 over y ∈ [−6, −1]: out of the camera's view (it sees |y| < 0.2 there), across
    every shadow ray from the visible floor (they cross height 3.5 at y − 2.94)."""
    scene = _scene(floor, tmp_path)
    mesh = bpy.data.meshes.new("veil")
    mesh.from_pydata([(-10, -6, 3.5), (10, -6, 3.5), (10, -1, 3.5), (-10, -1, 3.5)], [],
                     [(0, 1, 2, 3)])
    mesh.materials.append(veil)
    scene.collection.objects.link(bpy.data.objects.new("veil", mesh))
    scene.cycles.transparent_max_bounces = 8
    return scene


def _both(scene, tmp_path):
    ours = _render(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))[..., :3]
    cycles = _render(scene, "CYCLES", str(tmp_path / "cycles.exr"))[..., :3]
    return ours.reshape(-1, 3), cycles.reshape(-1, 3)


def test_a_transparent_veil_tints_the_shadow_like_cycles(material, tmp_path):
    _assign(material, "lambertian", reflectance=FLOOR)
    veil = bpy.data.materials.new("veil")
    _assign(veil, "cycles_transparent", color=VEIL)
    ours, cycles = _both(_veiled_scene(material, veil, tmp_path), tmp_path)
    expected = np.array(FLOOR) * np.array(VEIL) * math.cos(math.radians(40.0))
    np.testing.assert_allclose(cycles, np.broadcast_to(expected, cycles.shape), rtol=2e-3)
    np.testing.assert_allclose(ours, cycles, rtol=2e-3, atol=1e-5)


def test_the_transparent_part_of_a_mix_weights_the_shadow_like_cycles(material, tmp_path):
    """A node veil: Mix Shader (factor 0.3) of a Transparent and a Diffuse BSDF; the diffuse
    part blocks, the transparent part passes 0.7 × its colour."""
    _assign(material, "lambertian", reflectance=FLOOR)
    tree = Tree("mixed veil")
    mix = tree.surface(tree.add("ShaderNodeMixShader", Fac=0.3))
    tree.link(tree.add("ShaderNodeBsdfTransparent", Color=(*VEIL, 1.0)).outputs[0], mix.inputs[1])
    tree.link(tree.add("ShaderNodeBsdfDiffuse", Color=(0.9, 0.9, 0.9, 1.0)).outputs[0],
              mix.inputs[2])
    ours, cycles = _both(_veiled_scene(material, tree.material, tmp_path), tmp_path)
    expected = np.array(FLOOR) * 0.7 * np.array(VEIL) * math.cos(math.radians(40.0))
    np.testing.assert_allclose(cycles, np.broadcast_to(expected, cycles.shape), rtol=2e-3)
    np.testing.assert_allclose(ours, cycles, rtol=2e-3, atol=1e-5)


@pytest.mark.parametrize("layers, lit", [(8, True), (9, False)])
def test_the_shadow_turns_opaque_past_cycles_transparent_bounce_budget(material, tmp_path,
                                                                      layers, lit):
    """Cycles' default transparent_max_bounces 8 lets a shadow ray through 8 transparent
    surfaces; a 9th makes it opaque. Clear veils (colour 1) stacked over each other."""
    _assign(material, "lambertian", reflectance=FLOOR)
    veil = bpy.data.materials.new("veil")
    _assign(veil, "cycles_transparent", color=(1.0, 1.0, 1.0))
    scene = _veiled_scene(material, veil, tmp_path)
    for k in range(1, layers):
        copy = bpy.data.objects["veil"].copy()
        copy.location.z = -0.02 * k
        scene.collection.objects.link(copy)
    ours, cycles = _both(scene, tmp_path)
    assert bool(cycles.min() > 0.1) is lit
    np.testing.assert_allclose(ours, cycles, rtol=2e-3, atol=1e-5)
