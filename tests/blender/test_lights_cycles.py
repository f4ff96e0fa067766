"""BXDF_LAB against Cycles on worlds and lights: an HDRI world through a rotated Mapping and a
Mix with a colour, every area light shape, sphere lights (point and spot radius) and a sun angle,
the shadow terminator of a low-poly smooth sphere, and the constant-world furnace's noise.
Materials are exact pairings (Lambertian ↔ Diffuse BSDF), so any difference beyond the Monte
Carlo noise is the lights'."""

import math

import bpy
import numpy as np
import pytest
from mathutils import Vector

import pairing_scene
from bxdf_lab import export

SIZE = 32
HDRI = "/usr/share/blender/datafiles/studiolights/world/city.exr"


_diffuse = pairing_scene.lambertian_material


def _add(obj, material):
    obj.data.materials.append(material)
    return obj


def _sphere(material, location=(0, 0, 0), radius=1.0, segments=64, rings=32):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=segments, ring_count=rings, radius=radius,
                                         location=location)
    bpy.ops.object.shade_smooth()
    return _add(bpy.context.active_object, material)


def _plane(material, size=20.0, z=0.0):
    bpy.ops.mesh.primitive_plane_add(size=size, location=(0, 0, z))
    return _add(bpy.context.active_object, material)


def _scene(samples, bounces=0, camera=(0, -6, 3), target=(0, 0, 0.5), lens=50.0):
    scene = bpy.context.scene
    pairing_scene.add_camera(scene, camera, target, lens)
    pairing_scene.uniform_world(scene)
    pairing_scene.exr_output(scene, SIZE)
    pairing_scene.exact_pairing_settings(scene, samples, bounces, seed=3)
    return scene


def _render(scene, engine_id, path):
    return pairing_scene.render_rgba(scene, engine_id, path)


def _both(scene, tmp_path):
    return (_render(scene, "BXDF_LAB", tmp_path / "bxdf_lab.exr")[..., :3],
            _render(scene, "CYCLES", tmp_path / "cycles.exr")[..., :3])


def _assert_blocks_close(ours, cycles, rel, block=4, floor=0.02):
    """Means over block × block pixel tiles agree within `rel` (relative to the tile's level, or
    `floor` × the image's mean level for dark tiles): noise averages out, a wrong light does not."""
    def tiles(img):
        return img.reshape(SIZE // block, block, SIZE // block, block, 3).mean(axis=(1, 3))
    a, b = tiles(ours), tiles(cycles)
    scale = np.maximum(b, floor * cycles.mean())
    worst = np.abs(a - b) / scale
    assert worst.max() < rel, (f"worst tile differs by {worst.max():.3%} "
                               f"(ours {a.flat[worst.argmax()]:.4g}, Cycles {b.flat[worst.argmax()]:.4g})")


def _environment_world(scene, rotation_z_deg=60.0, strength=1.5, mix=0.2):
    tree = scene.world.node_tree
    nodes, links = tree.nodes, tree.links
    coords = nodes.new("ShaderNodeTexCoord")
    mapping = nodes.new("ShaderNodeMapping")
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(rotation_z_deg))
    env = nodes.new("ShaderNodeTexEnvironment")
    env.image = bpy.data.images.load(HDRI)
    mixer = nodes.new("ShaderNodeMixRGB")
    mixer.inputs["Fac"].default_value = mix
    mixer.inputs["Color2"].default_value = (0.2, 0.3, 0.5, 1.0)
    links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
    links.new(mapping.outputs["Vector"], env.inputs["Vector"])
    links.new(env.outputs["Color"], mixer.inputs["Color1"])
    background = nodes["Background"]
    links.new(mixer.outputs["Color"], background.inputs["Color"])
    background.inputs["Strength"].default_value = strength
    return env


def test_hdri_world_is_exported_as_an_importance_sampled_environment():
    scene = _scene(4)
    _environment_world(scene)
    data = export.export_scene(bpy.context.evaluated_depsgraph_get())
    world = data["world"]
    assert data["warnings"] == []
    np.testing.assert_allclose(world["color"], 1.5 * 0.2 * np.array([0.2, 0.3, 0.5]), rtol=1e-6)
    np.testing.assert_allclose(world["texture"]["weight"], [1.5 * 0.8] * 3, rtol=1e-6)
    c, s = math.cos(math.radians(60)), math.sin(math.radians(60))
    np.testing.assert_allclose(world["texture"]["matrix"][:, :3], [[c, -s, 0], [s, c, 0], [0, 0, 1]], atol=1e-6)
    assert world["sampling"] == "auto" and world["texture"]["path"] == HDRI


def test_hdri_world_with_a_rotated_mapping_matches_cycles(tmp_path):
    scene = _scene(1024)
    _sphere(_diffuse("white"), location=(0, 0, 0.5))
    _environment_world(scene)
    ours, cycles = _both(scene, tmp_path)
    assert cycles.mean() > 0.05
    _assert_blocks_close(ours, cycles, rel=0.04, block=8)


def test_hdri_and_sun_light_a_sphere_grid_as_cycles(tmp_path):
    scene = _scene(128, bounces=2, camera=(0, -8, 5))
    white = _diffuse("white")
    for x in (-1.5, 0.0, 1.5):
        for y in (-1.5, 0.0, 1.5):
            _sphere(white, location=(x, y, 0.5), radius=0.5, segments=32, rings=16)
    _plane(_diffuse("floor", 0.5))
    _environment_world(scene, rotation_z_deg=-30.0, strength=0.5, mix=0.0)
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy, sun.angle = 3.0, math.radians(5.0)
    sun_obj = bpy.data.objects.new("sun", sun)
    sun_obj.rotation_euler = (math.radians(35), 0, math.radians(20))
    scene.collection.objects.link(sun_obj)
    ours, cycles = _both(scene, tmp_path)
    _assert_blocks_close(ours, cycles, rel=0.06, block=8)


@pytest.mark.parametrize("shape", ["SQUARE", "RECTANGLE", "DISK", "ELLIPSE"])
def test_area_light_shapes_match_cycles(shape, tmp_path):
    scene = _scene(256, camera=(0, -6, 4), target=(0, 0, 0.3))
    _sphere(_diffuse("white"), location=(0, 0, 0.6), radius=0.6)
    _plane(_diffuse("floor", 0.5))
    light = bpy.data.lights.new("area", "AREA")
    light.shape, light.size, light.size_y, light.energy = shape, 1.5, 0.6, 200.0
    obj = bpy.data.objects.new("area", light)
    obj.location = (0.5, -0.5, 2.2)
    obj.rotation_euler = (math.radians(20), 0, math.radians(30))
    scene.collection.objects.link(obj)
    ours, cycles = _both(scene, tmp_path)
    assert cycles.mean() > 0.02
    _assert_blocks_close(ours, cycles, rel=0.04, block=8)


@pytest.mark.parametrize("kind", ["POINT", "SPOT", "SUN"])
def test_soft_shadows_match_cycles(kind, tmp_path):
    scene = _scene(256, camera=(0, -5, 5), target=(0, 0, 0))
    _sphere(_diffuse("white"), location=(0, 0, 0.7), radius=0.7)
    _plane(_diffuse("floor", 0.8))
    light = bpy.data.lights.new(kind.lower(), kind)
    obj = bpy.data.objects.new(kind.lower(), light)
    if kind == "SUN":
        light.energy, light.angle = 4.0, math.radians(20.0)
        obj.rotation_euler = (math.radians(30), 0, math.radians(40))
    else:
        light.energy, light.shadow_soft_size = 600.0, 0.6
        obj.location = (1.0, -1.0, 3.0)
        if kind == "SPOT":
            light.spot_size, light.spot_blend = math.radians(70), 0.3
            obj.rotation_euler = (math.radians(18), math.radians(18), 0)
    scene.collection.objects.link(obj)
    ours, cycles = _both(scene, tmp_path)
    assert cycles.mean() > 0.02
    _assert_blocks_close(ours, cycles, rel=0.05, block=8)


@pytest.mark.parametrize("geometry_offset", [0.1, 0.0])
def test_terminator_pixels_match_cycles(geometry_offset, tmp_path):
    # A coarse smooth sphere lit from the side by a delta sun: one sample per pixel is exact,
    # and the pixels just before the terminator show the offset (or its absence) as in Cycles.
    scene = _scene(1, camera=(0, -5, 0), target=(0, 0, 0), lens=60.0)
    scene.render.film_transparent = True  # alpha = coverage, to find the silhouette
    sphere = _sphere(_diffuse("white"), segments=12, rings=6)
    sphere.cycles.shadow_terminator_geometry_offset = geometry_offset
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy, sun.angle = 3.0, 0.0
    sun_obj = bpy.data.objects.new("sun", sun)
    sun_obj.rotation_euler = (0.0, math.radians(80.0), 0.0)  # light travels almost along −X
    scene.collection.objects.link(sun_obj)
    ours = _render(scene, "BXDF_LAB", tmp_path / "bxdf_lab.exr")
    cycles = _render(scene, "CYCLES", tmp_path / "cycles.exr")
    # Silhouette pixels included: there the view is below the smooth normal, and both bend
    # the closure's normal as Cycles does (test_silhouette_pixels_are_lit_as_cycles).
    covered = (cycles[..., 3] > 0.999) & (ours[..., 3] > 0.999)
    lit_ours, lit_cycles = ours[..., 0] > 1e-3, cycles[..., 0] > 1e-3
    assert (lit_cycles & covered).sum() > 40
    assert np.sum((lit_ours != lit_cycles) & covered) == 0
    both = lit_ours & lit_cycles & covered
    np.testing.assert_allclose(ours[both], cycles[both], rtol=2e-2, atol=2e-3)


def test_constant_furnace_is_no_noisier_than_cycles(tmp_path):
    # The harness's furnace: a white sphere in a world of radiance 1; the exact image is 1
    # everywhere, so the spread of pixel values is the noise. Cycles does not light-sample a
    # constant world, and neither does BXDF_LAB: cosine-sampled BSDF rays make both exact.
    scene = _scene(16, bounces=4, camera=(0, -7, 0), target=(0, 0, 0))
    _sphere(_diffuse("white", 1.0))
    scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (1, 1, 1, 1)
    ours, cycles = _both(scene, tmp_path)
    rms_ours = np.sqrt(np.mean((ours - 1.0) ** 2))
    rms_cycles = np.sqrt(np.mean((cycles - 1.0) ** 2))
    assert rms_ours <= rms_cycles + 1e-4, (rms_ours, rms_cycles)


def _diffuse_and_translucent(name):
    """A Mix Shader of a Diffuse and a Translucent BSDF: light from both sides of the surface."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    mix = nodes.new("ShaderNodeMixShader")
    mix.inputs["Fac"].default_value = 0.5
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.8, 0.6, 0.4, 1.0)
    translucent = nodes.new("ShaderNodeBsdfTranslucent")
    translucent.inputs["Color"].default_value = (0.4, 0.6, 0.8, 1.0)
    links.new(diffuse.outputs[0], mix.inputs[1])
    links.new(translucent.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], output.inputs["Surface"])
    return material


@pytest.mark.parametrize("view", ["front", "back"])
@pytest.mark.parametrize("sun_side", ["viewer", "far"])
def test_shading_offset_dims_the_viewers_side_only_as_cycles(view, sun_side, tmp_path):
    # A flat plane whose material reflects and transmits, seen from its front or its back, lit
    # by a delta sun 45.6° off the normal on the viewer's side or the far side, rendered with
    # shading offset 0 and 0.8 (frequency 1/(1 - 0.4)). Cycles turns the normal to the viewer
    # and dims only the side the viewer is on, by cos(45.6° · 5/3)/cos 45.6° = 0.347; the light
    # through the plane is not dimmed. One sample per pixel with one delta light is exact in
    # both renderers. Where light comes through the plane, Cycles leaves the pixels on the quad's
    # diagonal black (its shadow ray hits the neighbouring triangle): those are left out.
    above = view == "front"
    scene = _scene(1, camera=(0, 0, 3 if above else -3), target=(0, 0, 0))
    plane = _plane(_diffuse_and_translucent("two_sided"))
    plane.cycles.shadow_terminator_geometry_offset = 0.0
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy, sun.angle = 3.0, 0.0
    sun_obj = bpy.data.objects.new("sun", sun)
    from_above = above == (sun_side == "viewer")
    tilt = math.acos(0.7)
    sun_obj.rotation_euler = (tilt if from_above else math.pi - tilt, 0.0, 0.0)
    scene.collection.objects.link(sun_obj)
    renders = {}
    for offset in (0.0, 0.8):
        plane.cycles.shadow_terminator_offset = offset
        renders[offset] = _both(scene, tmp_path)
    lit = np.all([c.min(axis=-1) > 0.0 for _, c in renders.values()], axis=0)
    assert lit.sum() >= SIZE * SIZE - SIZE
    factor = math.cos(tilt / (1.0 - 0.4)) / 0.7 if sun_side == "viewer" else 1.0
    # Half of a colour of channel mean 0.6 over pi, times irradiance 3 · 0.7, times the factor.
    assert renders[0.8][1][lit].mean() == pytest.approx(0.5 * 0.6 / math.pi * 2.1 * factor,
                                                        rel=1e-3)
    for ours, cycles in renders.values():
        np.testing.assert_allclose(ours[lit], cycles[lit], rtol=2e-3)


def test_silhouette_pixels_are_lit_as_cycles(tmp_path):
    # A coarse smooth sphere lit from the left, slightly from the front: on its silhouette the
    # interpolated normal turns away from the camera while the facet still faces it. Cycles bends
    # each closure's normal until the view's mirror direction clears the surface
    # (ensure_valid_reflection), so those pixels are lit; so must ours be. Delta sun, one sample
    # per pixel: exact in both.
    scene = _scene(1, camera=(0, -5, 0), target=(0, 0, 0), lens=60.0)
    scene.render.film_transparent = True  # alpha = coverage
    _sphere(_diffuse("white"), segments=12, rings=6)
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy, sun.angle = 3.0, 0.0
    sun_obj = bpy.data.objects.new("sun", sun)
    sun_obj.rotation_mode = "QUATERNION"
    sun_obj.rotation_quaternion = Vector((1.0, 0.3, -0.4)).to_track_quat("-Z", "Y")
    scene.collection.objects.link(sun_obj)
    ours = _render(scene, "BXDF_LAB", tmp_path / "bxdf_lab.exr")
    cycles = _render(scene, "CYCLES", tmp_path / "cycles.exr")
    covered = (cycles[..., 3] > 0.999) & (ours[..., 3] > 0.999)
    assert np.array_equal(cycles[..., 3] > 0.5, ours[..., 3] > 0.5)
    inner = covered.copy()
    for dy, dx in ((0, 1), (0, -1), (1, 0), (-1, 0)):
        inner &= np.roll(covered, (dy, dx), axis=(0, 1))
    silhouette_lit = covered & ~inner & (cycles[..., 0] > 1e-3)
    assert silhouette_lit.sum() >= 8
    np.testing.assert_allclose(ours[covered][:, :3], cycles[covered][:, :3], rtol=2e-2, atol=2e-3)


def test_two_sphere_furnace_noise_per_sample_is_no_more_than_cycles(tmp_path):
    # Two touching white spheres (albedo 0.8) in a constant world: light is found by BSDF
    # sampling alone in both renderers, paths bounce between the spheres. At one sample per
    # pixel the spread of pixel values is the estimator's own (Cycles' per-pixel stratification
    # cannot act on one sample); measured from two seeds over 256 × 256 pixels. Both start
    # Russian roulette at the third hit and roll at the hit, never for an escaping ray; at 16 samples
    # Cycles' stratified sampler makes its noise fall faster than 1/√N (1.2-1.5 × ours), which
    # is the sampler's matter, not the estimator's.
    scene = _scene(1, bounces=8, camera=(0, -7, 0), target=(0, 0, 0))
    scene.render.resolution_x = scene.render.resolution_y = 256
    white = _diffuse("white", 0.8)
    _sphere(white, location=(-1, 0, 0))
    _sphere(white, location=(1, 0, 0))
    scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (1, 1, 1, 1)
    noise, level = {}, {}
    for engine_id in ("BXDF_LAB", "CYCLES"):
        halves = []
        for seed in (1, 2):
            scene.bxdf_lab_render.seed = scene.cycles.seed = seed
            halves.append(_render(scene, engine_id, tmp_path / f"{engine_id}_{seed}.exr")[..., :3])
        noise[engine_id] = np.sqrt(np.mean((halves[0] - halves[1]) ** 2 / 2.0))
        level[engine_id] = np.mean(halves)
    assert level["BXDF_LAB"] == pytest.approx(level["CYCLES"], rel=2e-3)
    assert noise["BXDF_LAB"] <= 1.05 * noise["CYCLES"], noise
