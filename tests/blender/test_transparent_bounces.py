"""Transparent bounces as Cycles counts them (integrator/path_state.h, path_state_next): a pass
through a Transparent BSDF is not a bounce. It keeps the path a camera path and counts against
scene.cycles.transparent_max_bounces, which BxDF Lab reads too; the surface after that many + 1
passes adds only its emission (measured in Cycles 3.4: behind 8 clear veils the floor is lit,
behind 9 it is black, at the default 8). Shadow rays from behind k veils get the budget less k.

The camera looks down through a stack of veils at a Lambertian floor under a sun without
angle, with max_bounces 0: without the separate count BxDF Lab's floor would be black behind
any veil. Every path is direct light, so both images are noise-free and must agree closely."""

import math

import bpy
import numpy as np
import pytest

from bxdf_lab import api
from test_nodes import Tree
from test_render import _render, _scene
from test_transparent_shadows import _assign

FLOOR = (0.7, 0.5, 0.3)


def _veils(material, veil, layers, tmp_path, half_size, sun_zenith_deg):
    """test_render's floor and sun (tilted to `sun_zenith_deg`) under `layers` veils of side
    2·half_size stacked at heights 2.0, 2.05, ... over the view's centre. The veils are moved
    off the centre a little so that no pixel's rays meet a veil's diagonal: Cycles' shadow rays
    count a hit on the edge both triangles share twice (measured: 1 in 4 samples dark there)."""
    scene = _scene(material, tmp_path)
    bpy.data.objects["sun"].rotation_euler = (math.radians(sun_zenith_deg), 0, 0)
    s, cx, cy = half_size, 0.0123, 0.0057
    for k in range(layers):
        z = 2.0 + 0.05 * k
        mesh = bpy.data.meshes.new(f"veil{k}")
        mesh.from_pydata([(cx - s, cy - s, z), (cx + s, cy - s, z), (cx + s, cy + s, z),
                          (cx - s, cy + s, z)], [], [(0, 1, 2, 3)])
        mesh.materials.append(veil)
        scene.collection.objects.link(bpy.data.objects.new(f"veil{k}", mesh))
    return scene


def _both(scene, tmp_path):
    ours = _render(scene, "BXDF_LAB", str(tmp_path / "bxdf_lab.exr"))[..., :3]
    cycles = _render(scene, "CYCLES", str(tmp_path / "cycles.exr"))[..., :3]
    return ours.reshape(-1, 3), cycles.reshape(-1, 3)


def _veil(color):
    veil = bpy.data.materials.new("veil")
    _assign(veil, "cycles_transparent", color=color)
    return veil


@pytest.mark.parametrize("budget, layers, lit", [(8, 1, True), (8, 8, True), (8, 9, False),
                                                  (0, 1, False), (2, 2, True), (2, 3, False)])
def test_the_camera_sees_through_transparent_max_bounces_veils_like_cycles(
        material, tmp_path, budget, layers, lit):
    """Small clear veils over the view, a sun 60° from the zenith: the floor's shadow rays miss
    the veils, so only the camera path's own count decides."""
    _assign(material, "lambertian", reflectance=FLOOR)
    scene = _veils(material, _veil((1.0, 1.0, 1.0)), layers, tmp_path, 1.2, 60.0)
    scene.cycles.transparent_max_bounces = budget
    ours, cycles = _both(scene, tmp_path)
    expected = np.array(FLOOR) * 0.5 if lit else np.zeros(3)
    np.testing.assert_allclose(cycles, np.broadcast_to(expected, cycles.shape), rtol=2e-3, atol=1e-6)
    np.testing.assert_allclose(ours, cycles, rtol=2e-3, atol=1e-6)


def test_veils_tint_the_path_by_their_colour_like_cycles(material, tmp_path):
    """Two coloured veils: BxDF Lab's floor is FLOOR · colour² · cos 60° exactly. Cycles' is the
    same in the mean: it plays Russian roulette on the dimmed throughput at each transparent
    pass (continuation √max), so its pixels are noisy at 4 samples; 1024 samples give about 1%."""
    _assign(material, "lambertian", reflectance=FLOOR)
    color = (0.9, 0.8, 0.6)
    scene = _veils(material, _veil(color), 2, tmp_path, 1.2, 60.0)
    ours, cycles = _both(scene, tmp_path)
    expected = np.array(FLOOR) * np.array(color) ** 2 * 0.5
    np.testing.assert_allclose(ours, np.broadcast_to(expected, ours.shape), rtol=2e-3)
    np.testing.assert_allclose(cycles.mean(axis=0), expected, rtol=0.04)


@pytest.mark.parametrize("layers, lit", [(4, True), (5, False)])
def test_the_paths_transparent_bounces_lower_the_shadow_budget_like_cycles(
        material, tmp_path, layers, lit):
    """Veils over the whole floor and the sun overhead: the camera passes k clear veils and the
    floor's shadow ray must pass the same k with the budget 8 − k left (Cycles' integrate_
    shadow_max_transparent_hits)."""
    _assign(material, "lambertian", reflectance=FLOOR)
    scene = _veils(material, _veil((1.0, 1.0, 1.0)), layers, tmp_path, 10.0, 0.0)
    scene.cycles.transparent_max_bounces = 8
    ours, cycles = _both(scene, tmp_path)
    assert bool(cycles.min() > 0.1) is lit
    np.testing.assert_allclose(ours, cycles, rtol=2e-3, atol=1e-6)


@pytest.mark.parametrize("budget, lit", [(8, True), (5, True), (4, False)])
def test_past_max_bounces_a_path_still_passes_veils_like_cycles(material, tmp_path, budget, lit):
    """A sharp mirror floor reflects an emitting ceiling through 3 veils, crossed on the way down
    and again on the way up, with max_bounces 0: the mirror uses the only bounce, and the path
    still passes the veils (Cycles keeps Transparent closures past max_bounces). After 6 passes
    the ceiling's emission counts even at budget 5 (only emission at the surface after budget + 1
    passes); at budget 4 the 6th veil ends the path. BxDF Lab's image is the closed form;
    Cycles' agrees in the mean (its Russian roulette on the dimmed throughput makes it noisy:
    16 samples, 4096 in all, give about 1%)."""
    mirror = (0.8, 0.7, 0.6)
    _assign(material, "cycles_glossy", color=mirror, distribution="sharp", roughness=0.0)
    veil_color = (0.95, 0.9, 0.85)
    scene = _veils(material, _veil(veil_color), 3, tmp_path, 3.0, 60.0)  # wide: rays return
    light = (0.5, 0.6, 0.7)
    tree = Tree("ceiling")
    tree.surface(tree.add("ShaderNodeEmission", Color=(*light, 1.0), Strength=1.0))
    mesh = bpy.data.meshes.new("ceiling")
    mesh.from_pydata([(-30, -30, 6), (-30, 30, 6), (30, 30, 6), (30, -30, 6)], [], [(0, 1, 2, 3)])
    mesh.materials.append(tree.material)
    scene.collection.objects.link(bpy.data.objects.new("ceiling", mesh))
    scene.cycles.transparent_max_bounces = budget
    scene.cycles.samples = 16
    ours, cycles = _both(scene, tmp_path)
    expected = np.array(mirror) * np.array(veil_color) ** 6 * np.array(light) if lit else np.zeros(3)
    np.testing.assert_allclose(ours, np.broadcast_to(expected, ours.shape), rtol=2e-3, atol=1e-6)
    np.testing.assert_allclose(cycles.mean(axis=0), expected, rtol=0.04, atol=1e-6)


def test_past_max_bounces_a_mixed_veil_passes_only_its_transparent_part_like_cycles(material,
                                                                                   tmp_path):
    """The mirror scene with one node veil, Mix Shader (factor 0.3) of a Transparent and a
    Diffuse BSDF: on the way down the path scatters there (the diffuse part is lit directly, the
    transparent part chosen by its sample weight); on the way up, past max_bounces 0, only the
    Transparent closure is kept and passes 0.7 × its colour (Cycles allocates nothing else at
    that surface). Both images are noisy (closure choice, light choice, Cycles' roulette): their
    means over 16×16 pixels × 64 samples agree within 1% (measured 0.03%; passing the whole
    colour instead of 0.7 × it would raise ours by about 30%)."""
    _assign(material, "cycles_glossy", color=(0.8, 0.7, 0.6), distribution="sharp", roughness=0.0)
    tree = Tree("mixed veil")
    mix = tree.surface(tree.add("ShaderNodeMixShader", Fac=0.3))
    tree.link(tree.add("ShaderNodeBsdfTransparent", Color=(0.9, 0.8, 0.7, 1.0)).outputs[0],
              mix.inputs[1])
    tree.link(tree.add("ShaderNodeBsdfDiffuse", Color=(0.5, 0.5, 0.5, 1.0)).outputs[0],
              mix.inputs[2])
    scene = _veils(material, tree.material, 1, tmp_path, 3.0, 60.0)
    ceiling = Tree("ceiling")
    ceiling.surface(ceiling.add("ShaderNodeEmission", Color=(0.5, 0.6, 0.7, 1.0), Strength=1.0))
    mesh = bpy.data.meshes.new("ceiling")
    mesh.from_pydata([(-30, -30, 6), (-30, 30, 6), (30, 30, 6), (30, -30, 6)], [], [(0, 1, 2, 3)])
    mesh.materials.append(ceiling.material)
    scene.collection.objects.link(bpy.data.objects.new("ceiling", mesh))
    scene.cycles.samples = scene.bxdf_lab_render.samples = 64
    ours, cycles = _both(scene, tmp_path)
    # The reflected ceiling alone, reached through the veil twice (0.7 colour each way) would be
    # mirror · (0.7 colour)² · light; the diffuse part adds its direct light on top.
    floor_only = np.array((0.8, 0.7, 0.6)) * (0.7 * np.array((0.9, 0.8, 0.7))) ** 2 * np.array((0.5, 0.6, 0.7))
    assert np.all(cycles.mean(axis=0) > floor_only)
    np.testing.assert_allclose(ours.mean(axis=0), cycles.mean(axis=0), rtol=0.01)
