"""bxdf.render(): the Embree renderer from Python (scene dicts as the Blender add-on exports them).

Direct light from a point light is noise-free, so a pixel-centre render with max_bounces=0 must
equal f·I·cosθ/d² at the hit point, computed here from bxdf.make(...).f and a numpy ray caster
over the same triangles.
"""

import threading
import time

import numpy as np
import pytest

import bxdf

pytestmark = pytest.mark.skipif(not hasattr(bxdf, "render"), reason="built without the renderer")

SIZE = 24
LIGHT_POS = np.array([2.0, 3.0, 4.0])
LIGHT_I = np.array([30.0, 20.0, 10.0])
CAMERA_Z = 4.0
LENS, SENSOR = 50.0, 36.0


def uv_sphere(segments=24, rings=12):
    """Unit sphere: positions (V, 3), triangles (T, 3), exact normals per position."""
    theta = np.linspace(0.0, np.pi, rings + 1)
    phi = np.linspace(0.0, 2 * np.pi, segments, endpoint=False)
    t, p = np.meshgrid(theta[1:-1], phi, indexing="ij")
    ring_pts = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], -1).reshape(-1, 3)
    positions = np.concatenate([[[0, 0, 1]], ring_pts, [[0, 0, -1]]]).astype(np.float32)
    south = len(positions) - 1
    tris = []
    ring = lambda r, s: 1 + r * segments + s % segments  # noqa: E731
    for s in range(segments):
        tris.append((0, ring(0, s), ring(0, s + 1)))
        for r in range(rings - 2):
            a, b, c, d = ring(r, s), ring(r + 1, s), ring(r + 1, s + 1), ring(r, s + 1)
            tris += [(a, b, c), (a, c, d)]
        tris.append((south, ring(rings - 2, s + 1), ring(rings - 2, s)))
    triangles = np.array(tris, dtype=np.int32)
    # Counter-clockwise seen from outside: flip any triangle whose winding points inwards.
    v0, v1, v2 = (positions[triangles[:, k]] for k in range(3))
    inward = np.einsum("ij,ij->i", np.cross(v1 - v0, v2 - v0), v0 + v1 + v2) < 0
    triangles[inward] = triangles[inward][:, [0, 2, 1]]
    return positions, triangles, positions.copy()


def sphere_mesh():
    """The sphere with separately indexed attributes: normals stored in a shuffled order, UVs per
    corner (so every vertex is split by UV seams before welding)."""
    positions, triangles, normals = uv_sphere()
    order = np.random.default_rng(1).permutation(len(normals))
    inverse = np.argsort(order)
    uvs = np.random.default_rng(2).random((triangles.size, 2)).astype(np.float32)
    return {
        "name": "sphere",
        "positions": positions,
        "triangles": triangles,
        "normals": normals[order],
        "normal_indices": inverse[triangles].astype(np.int32),
        "uvs": uvs,
        "uv_indices": np.arange(triangles.size, dtype=np.int32).reshape(-1, 3),
        "material_indices": np.zeros(len(triangles), dtype=np.int32),
    }


def test_a_mesh_with_nothing_to_split_renders_as_welded():
    """Normals and UVs indexed like the positions (Blender's smooth meshes) leave nothing to weld:
    the mesh is taken as it is, and renders bit for bit as the same corners welded (forced here
    by one position no triangle uses), UVs and normals included."""
    positions, triangles, normals = uv_sphere()
    uvs = (0.5 + 0.5 * positions[:, :2]).astype(np.float32)  # varies over the sphere
    shared = {"name": "shared", "positions": positions, "triangles": triangles,
              "normals": normals, "normal_indices": triangles, "uvs": uvs, "uv_indices": triangles,
              "material_indices": np.zeros(len(triangles), dtype=np.int32)}
    unused = np.float32([[9.0, 9.0, 9.0]])
    welded = dict(shared, positions=np.vstack([unused, positions]), normals=np.vstack([unused, normals]),
                  uvs=np.vstack([unused[:, :2], uvs]), triangles=triangles + 1)
    welded["normal_indices"] = welded["uv_indices"] = welded["triangles"]
    # Reflectance (u, v, 0.5): the image shows the UVs as well as the normals' shading.
    graph = {"graph": {
        "nodes": [{"op": "uv"}, {"op": "separate", "vector": {"node": 0}},
                  {"op": "combine", "x": {"node": 1, "out": "x"}, "y": {"node": 1, "out": "y"}, "z": 0.5}],
        "closures": [{"model": "lambertian", "params": {"reflectance": {"node": 2, "out": "color"}}}]}}
    images = [bxdf.render(scene_dict(graph, mesh), DIRECT, return_stats=True) for mesh in (shared, welded)]
    (image, stats), (expected, expected_stats) = images
    assert image[..., 0].max() > 0.01 and not np.allclose(image[..., 0], image[..., 1])
    np.testing.assert_array_equal(image, expected)
    assert stats["stored_triangles"] == expected_stats["stored_triangles"] == len(triangles)


def camera():
    matrix = np.eye(4, dtype=np.float32)
    matrix[2, 3] = CAMERA_Z
    return {"matrix": matrix, "type": "persp", "lens": LENS, "sensor_width": SENSOR,
            "sensor_height": 24.0, "sensor_fit": "auto", "shift": (0.0, 0.0),
            "clip": (0.1, 100.0), "resolution": (SIZE, SIZE)}


def scene_dict(material, mesh=None):
    return {
        "meshes": [mesh or sphere_mesh()],
        "materials": [material],
        "lights": [{"type": "point", "name": "lamp", "position": LIGHT_POS.astype(np.float32),
                    "intensity": LIGHT_I.astype(np.float32), "radius": 0.0}],
        "camera": camera(),
        "world": {"color": np.zeros(3, dtype=np.float32)},
        "resolution": (SIZE, SIZE),
        "warnings": [],
    }


DIRECT = {"samples": 1, "max_bounces": 0, "pixel_filter": "pixel_center", "threads": 2, "seed": 0}


def expected_direct(model, mesh):
    """f·I·cosθ/d² per pixel (top row first) by ray casting the mesh in numpy; NaN off the sphere
    and where the hit is near a silhouette or terminator (left out of the comparison)."""
    pos = mesh["positions"].astype(np.float64)
    nrm = mesh["normals"].astype(np.float64)
    tri, ntri = mesh["triangles"], mesh["normal_indices"]
    plane = SENSOR / LENS
    x = ((np.arange(SIZE) + 0.5) / SIZE - 0.5) * plane
    y = (0.5 - (np.arange(SIZE) + 0.5) / SIZE) * plane
    X, Y = np.meshgrid(x, y)
    d = np.stack([X, Y, -np.ones_like(X)], -1).reshape(-1, 3)
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    o = np.array([0.0, 0.0, CAMERA_Z])
    v0, v1, v2 = pos[tri[:, 0]], pos[tri[:, 1]], pos[tri[:, 2]]
    e1, e2 = v1 - v0, v2 - v0
    # Möller–Trumbore, every ray against every triangle.
    pvec = np.cross(d[:, None, :], e2[None])
    det = np.einsum("tk,rtk->rt", e1, pvec)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / det
        tvec = o - v0
        u = np.einsum("tk,rtk->rt", tvec, pvec) * inv
        qvec = np.cross(tvec, e1)
        v = np.einsum("rk,tk->rt", d, qvec) * inv
        t = np.einsum("tk,tk->t", e2, qvec)[None] * inv
    ok = (np.abs(det) > 1e-12) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)
    t = np.where(ok, t, np.inf)
    hit_tri = np.argmin(t, axis=1)
    rows = np.arange(len(d))
    t_hit = t[rows, hit_tri]
    hit = np.isfinite(t_hit)
    b1, b2 = u[rows, hit_tri], v[rows, hit_tri]
    n = (1 - b1 - b2)[:, None] * nrm[ntri[hit_tri, 0]] + b1[:, None] * nrm[ntri[hit_tri, 1]] \
        + b2[:, None] * nrm[ntri[hit_tri, 2]]
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    p = o + np.where(hit, t_hit, 0.0)[:, None] * d  # misses get the eye: finite, left out below
    to_light = LIGHT_POS - p
    dist = np.linalg.norm(to_light, axis=1)
    wi_w, wo_w = to_light / dist[:, None], -d
    # Any tangent frame about n (the models here are isotropic).
    helper = np.where(np.abs(n[:, :1]) < 0.9, [[1.0, 0, 0]], [[0, 1.0, 0]])
    tx = np.cross(helper, n)
    tx /= np.linalg.norm(tx, axis=1, keepdims=True)
    ty = np.cross(n, tx)
    local = lambda w: np.stack([(w * tx).sum(1), (w * ty).sum(1), (w * n).sum(1)], 1)  # noqa: E731
    wo, wi = local(wo_w), local(wi_w)
    keep = hit & (wo[:, 2] > 0.3) & (wi[:, 2] > 0.3)
    radiance = np.full((len(d), 3), np.nan)
    f = model.f(wo[keep], wi[keep]).astype(np.float64)
    radiance[keep] = f * LIGHT_I * wi[keep, 2:3] / dist[keep, None] ** 2
    return radiance.reshape(SIZE, SIZE, 3)


MATERIALS = [
    ("lambertian", {"reflectance": [0.8, 0.5, 0.3]}),
    ("microfacet", {"distribution": "ggx", "alpha_x": 0.25, "alpha_y": 0.25}),
]


@pytest.mark.parametrize("model_name,params", MATERIALS, ids=[m[0] for m in MATERIALS])
def test_direct_point_light_matches_formula(model_name, params):
    mesh = sphere_mesh()
    material = {"name": "m", "model": model_name, "params": params}
    image, stats = bxdf.render(scene_dict(material, mesh), DIRECT, return_stats=True)
    assert image.shape == (SIZE, SIZE, 4) and image.dtype == np.float32
    expected = expected_direct(bxdf.make(model_name, **params), mesh)
    mask = np.isfinite(expected[..., 0])
    assert mask.sum() > 100  # most of the sphere's disc is compared
    np.testing.assert_allclose(image[..., :3][mask], expected[mask], rtol=2e-3, atol=1e-6)
    # Off the sphere: black world, alpha 1 everywhere.
    assert np.all(image[0, 0, :3] == 0) and np.all(image[..., 3] == 1)
    assert stats["samples_per_pixel"] == 1 and not stats["cancelled"]
    assert stats["rays"] >= SIZE * SIZE and stats["shadow_rays"] > 0 and stats["seconds"] > 0


def test_row_order_and_bottom_up():
    material = {"name": "m", "model": "lambertian", "params": {"reflectance": 0.5}}
    scene = scene_dict(material)
    scene["lights"][0]["position"] = np.array([0.0, 5.0, 2.0], dtype=np.float32)  # above: top lit
    top_down = bxdf.render(scene, DIRECT)
    bottom_up = bxdf.render(scene, DIRECT, bottom_up=True)
    np.testing.assert_array_equal(bottom_up, top_down[::-1])
    lum = top_down[..., :3].sum(-1)
    assert lum[: SIZE // 2].sum() > 2 * lum[SIZE // 2:].sum()
    # An odd number of rows: the middle row stays where it is.
    scene["resolution"] = (SIZE, 7)
    scene["camera"]["resolution"] = (SIZE, 7)
    top_down = bxdf.render(scene, DIRECT)
    np.testing.assert_array_equal(bxdf.render(scene, DIRECT, bottom_up=True), top_down[::-1])
    assert top_down.shape == (7, SIZE, 4) and not np.array_equal(top_down[0], top_down[-1])


def rotation(axis, angle):
    axis = np.asarray(axis, dtype=np.float64) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


@pytest.mark.parametrize("mirror", [False, True], ids=["rotate-scale", "mirror"])
def test_instances_match_world_space_mesh(mirror):
    material = {"name": "m", "model": "microfacet", "params": {"alpha_x": 0.3, "alpha_y": 0.3}}
    world = sphere_mesh()
    reference = bxdf.render(scene_dict(material, world), DIRECT)

    m = np.eye(4)
    m[:3, :3] = 1.5 * rotation([1, 2, 3], 0.7) @ np.diag([-1.0 if mirror else 1.0, 1, 1])
    m[:3, 3] = [0.3, -0.2, 0.1]
    inv = np.linalg.inv(m)
    local = dict(world)
    local["positions"] = (world["positions"] @ inv[:3, :3].T + inv[:3, 3]).astype(np.float32)
    local["normals"] = (world["normals"] @ m[:3, :3]).astype(np.float32)  # n_local ∝ Mᵀ n_world
    scene = scene_dict(material, local)
    scene["instance_mesh"] = np.array([0], dtype=np.int32)
    scene["instance_matrix"] = m[None].astype(np.float32)
    instanced = bxdf.render(scene, DIRECT)
    np.testing.assert_allclose(instanced, reference, rtol=1e-3, atol=1e-5)


def _placed(world, m):
    """The world-space mesh `world` as the object-space mesh that `m` places there."""
    inv = np.linalg.inv(m)
    local = dict(world)
    local["positions"] = (world["positions"] @ inv[:3, :3].T + inv[:3, 3]).astype(np.float32)
    local["normals"] = (world["normals"] @ m[:3, :3]).astype(np.float32)  # n_local ∝ Mᵀ n_world
    return local


@pytest.mark.parametrize("mirror", [False, True], ids=["rotate-scale", "mirror"])
def test_shared_instances_match_world_space_meshes(mirror):
    """A mesh placed twice is stored once and drawn by Embree instances: the image equals the
    one of the two placements given as world-space meshes."""
    material = {"name": "m", "model": "microfacet", "params": {"alpha_x": 0.3, "alpha_y": 0.3}}
    world = sphere_mesh()
    matrices = []
    for shift, angle in ((-0.9, 0.7), (0.9, -0.4)):
        m = np.eye(4)
        m[:3, :3] = 0.6 * rotation([1, 2, 3], angle) @ np.diag([-1.0 if mirror else 1.0, 1, 1])
        m[:3, 3] = [shift, -0.2, 0.1]
        matrices.append(m)
    # The reference: each placement moved into world space by numpy, drawn as its own mesh.
    moved = []
    for m in matrices:
        w = dict(world)
        w["positions"] = (world["positions"] @ m[:3, :3].T + m[:3, 3]).astype(np.float32)
        normals = world["normals"] @ np.linalg.inv(m[:3, :3])
        w["normals"] = (normals / np.linalg.norm(normals, axis=1, keepdims=True)).astype(np.float32)
        if mirror:  # the winding follows the mirror, so that the front stays the front
            for key in ("triangles", "normal_indices", "uv_indices"):
                w[key] = w[key][:, [0, 2, 1]]
        moved.append(w)
    reference_scene = scene_dict(material)
    reference_scene["meshes"] = moved
    reference = bxdf.render(reference_scene, DIRECT)
    assert reference[..., :3].sum() > 0

    scene = scene_dict(material, world)
    scene["instance_mesh"] = np.array([0, 0], dtype=np.int32)
    scene["instance_matrix"] = np.stack(matrices).astype(np.float32)
    instanced, stats = bxdf.render(scene, DIRECT, return_stats=True)
    assert stats["instances"] == 2 and stats["stored_triangles"] == len(world["triangles"])
    assert stats["triangles"] == 2 * len(world["triangles"])
    np.testing.assert_allclose(instanced, reference, rtol=1e-3, atol=1e-4)


def test_instances_draw_a_mesh_several_times_and_only_instances():
    material = {"name": "m", "model": "lambertian", "params": {"reflectance": 0.7}}
    scene = scene_dict(material)
    scene["instance_mesh"] = np.zeros(0, dtype=np.int32)
    scene["instance_matrix"] = np.zeros((0, 4, 4), dtype=np.float32)
    assert np.all(bxdf.render(scene, DIRECT)[..., :3] == 0)  # no instance: nothing drawn

    shifted = [np.eye(4, dtype=np.float32) for _ in range(2)]
    shifted[0][0, 3], shifted[1][0, 3] = -1.2, 1.2
    for mat in shifted:
        mat[:3, :3] *= 0.5
    scene["instance_mesh"] = np.array([0, 0], dtype=np.int32)
    scene["instance_matrix"] = np.stack(shifted)
    image = bxdf.render(scene, DIRECT)[..., :3].sum(-1)
    centre = SIZE // 2
    assert image[centre, centre] == 0  # the gap between the two spheres
    assert image[centre, :centre].max() > 0 and image[centre, centre:].max() > 0


def test_default_material_for_minus_one():
    mesh = sphere_mesh()
    mesh["material_indices"] = np.full(len(mesh["triangles"]), -1, dtype=np.int32)
    scene = scene_dict({"name": "unused", "model": "lambertian", "params": {}}, mesh)
    image = bxdf.render(scene, DIRECT)
    expected = expected_direct(bxdf.make("lambertian", reflectance=0.8), mesh)
    mask = np.isfinite(expected[..., 0])
    np.testing.assert_allclose(image[..., :3][mask], expected[mask], rtol=2e-3, atol=1e-6)


def test_the_bvh_build_follows_the_rays_per_triangle():
    """Few rays per triangle (pixels x samples x (1 + max bounces) under 96 per triangle) get
    Embree's quick build, more the medium one; the image does not depend on it (the closest hit
    is the closest hit)."""
    material = {"name": "m", "model": "lambertian", "params": {"reflectance": 0.8}}
    scene = scene_dict(material)
    samples = 96 * len(scene["meshes"][0]["triangles"]) // (SIZE * SIZE) - 1
    settings = dict(DIRECT, samples=samples, pixel_filter="box")
    quick, stats = bxdf.render(scene, settings, return_stats=True)
    assert stats["bvh_build"] == "quick"
    # Twice the rays per pixel: the medium build. In this scene (one point light, a black
    # world) a bounce finds no light, so max_bounces 1 draws and adds the same as 0.
    medium, stats = bxdf.render(scene, dict(settings, max_bounces=1), return_stats=True)
    assert stats["bvh_build"] == "medium"
    assert quick[..., :3].max() > 0
    np.testing.assert_array_equal(quick, medium)


def test_other_lights_and_area_light_render():
    material = {"name": "m", "model": "lambertian", "params": {"reflectance": 0.8}}
    scene = scene_dict(material)
    area = np.eye(4, dtype=np.float32)
    area[:3, 3] = [0, 0, 3]
    scene["lights"] = [
        {"type": "sun", "direction": np.array([0, 0, -1], np.float32), "irradiance": [1, 1, 1], "angle": 0.0},
        {"type": "spot", "position": [0, 0, 3], "direction": [0, 0, -1], "intensity": [5, 5, 5],
         "spot_size": 0.8, "spot_blend": 0.2, "radius": 0.1},
        {"type": "area", "shape": "disk", "size": (1.0, 1.0), "matrix": area, "power": 20.0, "color": [1, 1, 1]},
    ]
    image, stats = bxdf.render(scene, {"samples": 4, "max_bounces": 1, "threads": 2}, return_stats=True)
    assert np.all(np.isfinite(image)) and image[SIZE // 2, SIZE // 2, :3].min() > 0
    # Radius, angle and one-sided area lights are rendered as Cycles does: nothing to warn about.
    assert stats["warnings"] == []


BIG = {"samples": 64, "max_bounces": 2, "pixel_filter": "box", "threads": 1, "samples_per_pass": 1}
# About 3 s on one thread if nobody stops it: a cancel that returns well before that stopped it.
LONG = dict(BIG, samples=1024, max_bounces=3)


def long_scene():
    scene = scene_dict({"name": "m", "model": "lambertian", "params": {"reflectance": 0.5}})
    scene["resolution"] = (96, 96)
    scene["world"] = {"color": [0.5, 0.5, 0.5]}
    return scene


def test_cancel_by_returning_false():
    calls = []

    def on_progress(done, total, image):
        calls.append((done, total, image))
        return len(calls) < 3

    started = time.perf_counter()
    image, stats = bxdf.render(long_scene(), LONG, on_progress, return_stats=True)
    assert time.perf_counter() - started < 1.0
    assert stats["cancelled"] and stats["samples_per_pixel"] < 1024
    assert len(calls) == 3  # not called again once cancelled
    assert image.shape == (96, 96, 4) and np.all(np.isfinite(image))
    assert calls[0][1] > 0 and calls[0][0] <= calls[0][1]


def test_progress_reports_tiles_and_partial_images():
    material = {"name": "m", "model": "lambertian", "params": {"reflectance": 0.5}}
    calls = []
    settings = dict(BIG, samples=4, tile_size=8)
    image = bxdf.render(scene_dict(material), settings,
                        lambda done, total, img: calls.append((done, total, img)))
    totals = {total for _, total, _ in calls}
    assert totals == {4 * 9}  # 4 passes of 3×3 tiles
    dones = [done for done, _, _ in calls]
    assert dones == sorted(dones) and dones[-1] == 4 * 9
    partial = [img for _, _, img in calls if img is not None]
    assert partial and all(p.shape == image.shape and p.dtype == np.float32 for p in partial)


def test_without_partial_images_progress_gets_none_and_the_image_is_the_same():
    material = {"name": "m", "model": "lambertian", "params": {"reflectance": 0.5}}
    settings = dict(BIG, samples=4, tile_size=8)
    with_partial, without = [], []
    expected = bxdf.render(scene_dict(material), settings,
                           lambda done, total, img: with_partial.append(img))
    image = bxdf.render(scene_dict(material), settings,
                        lambda done, total, img: without.append((done, total, img)),
                        partial_images=False)
    assert any(img is not None for img in with_partial)
    assert without and all(img is None for _, _, img in without)
    assert without[-1][:2] == (4 * 9, 4 * 9)  # tile progress still arrives, to the end
    np.testing.assert_array_equal(image, expected)


class Boom(Exception):
    pass


def test_exception_in_progress_propagates_after_stopping():
    calls = []

    def on_progress(done, total, image):
        calls.append(done)
        raise Boom("stop here")

    started = time.perf_counter()
    with pytest.raises(Boom, match="stop here"):
        bxdf.render(long_scene(), LONG, on_progress)
    assert time.perf_counter() - started < 1.0  # the render stopped, not ran to its end
    assert len(calls) == 1  # not called again once cancelled


def test_on_progress_must_be_callable():
    material = {"name": "m", "model": "lambertian", "params": {}}
    with pytest.raises(ValueError, match="on_progress"):
        bxdf.render(scene_dict(material), DIRECT, 42)


def test_gil_released_while_rendering():
    counter = [0]
    stop = threading.Event()

    def spin():
        while not stop.is_set():
            counter[0] += 1
            time.sleep(0.001)

    thread = threading.Thread(target=spin)
    thread.start()
    try:
        time.sleep(0.01)
        before = counter[0]
        _, stats = bxdf.render(long_scene(), dict(LONG, samples=64), return_stats=True)
        during = counter[0] - before
    finally:
        stop.set()
        thread.join()
    assert stats["seconds"] > 0.1  # long enough for the check to mean something
    # The spinner ticks about once a millisecond when it can run; with the GIL held throughout
    # it could not tick at all.
    assert during >= max(5, 0.1 * stats["seconds"] / 0.001)


def test_render_scene_file(tmp_path):
    path = tmp_path / "scene.json"
    path.write_text("""{
      "render": {"width": 16, "height": 12, "spp": 2, "max_bounces": 1},
      "camera": {"position": [0, -5, 1], "look_at": [0, 0, 0], "up": [0, 0, 1]},
      "materials": {"clay": {"model": "lambertian", "params": {"reflectance": 0.5}}},
      "meshes": [{"shape": "sphere", "center": [0, 0, 0], "radius": 1, "material": "clay"}],
      "lights": [{"type": "point", "position": [2, -2, 3], "power": 1000}]
    }""")
    image, stats = bxdf.render_scene_file(path, return_stats=True)
    assert image.shape == (12, 16, 4) and stats["samples_per_pixel"] == 2
    assert image[6, 8, :3].min() > 0
    image = bxdf.render_scene_file(str(path), {"samples": 1})
    assert image.shape == (12, 16, 4)
    with pytest.raises(ValueError, match="scene.json"):
        path.write_text('{"meshes": [{"shape": "cube"}]}')
        bxdf.render_scene_file(path)


# ---- bad input: every refusal is a ValueError naming the field ------------------------------

def good_scene():
    return scene_dict({"name": "m", "model": "lambertian", "params": {}})


def _set(path, value):
    def edit(scene):
        target = scene
        for key in path[:-1]:
            target = target[key]
        if value is KeyError:
            del target[path[-1]]
        else:
            target[path[-1]] = value
    return edit


N_TRI = len(uv_sphere()[1])
BAD_SCENES = [
    ("resolution missing", _set(["resolution"], KeyError), r"scene\['resolution'\]: is missing"),
    ("resolution zero", _set(["resolution"], (0, 4)), r"scene\['resolution'\]"),
    ("scene not a dict", None, r"scene: is a list; expected a dict"),
    ("camera missing", _set(["camera"], KeyError), r"scene\['camera'\]: is missing"),
    ("no camera", _set(["camera"], {"missing": True, "resolution": (4, 4)}), r"scene\['camera'\]: the scene has no camera"),
    ("camera panoramic", _set(["camera", "type"], "pano"), r"scene\['camera'\]\['type'\]: 'pano' is not supported"),
    ("camera ortho scale", _set(["camera", "ortho_scale"], 0.0), r"scene\['camera'\]\['ortho_scale'\]: 0.0 is out of range"),
    ("camera matrix shape", _set(["camera", "matrix"], np.eye(3)), r"scene\['camera'\]\['matrix'\]: has shape \(3, 3\)"),
    ("camera lens", _set(["camera", "lens"], -5.0), r"scene\['camera'\]\['lens'\]: -5.0 is out of range"),
    ("camera fit", _set(["camera", "sensor_fit"], "diagonal"), r"scene\['camera'\]\['sensor_fit'\]"),
    ("camera clip", _set(["camera", "clip"], (5.0, 1.0)), r"scene\['camera'\]\['clip'\]"),
    ("positions missing", _set(["meshes", 0, "positions"], KeyError), r"scene\['meshes'\]\[0\]\['positions'\]: is missing"),
    ("positions shape", _set(["meshes", 0, "positions"], np.zeros((4, 2), np.float32)),
     r"scene\['meshes'\]\[0\]\['positions'\]: has shape \(4, 2\); expected a real array of shape \(N, 3\)"),
    ("positions dtype", _set(["meshes", 0, "positions"], np.array([["a", "b", "c"]])),
     r"scene\['meshes'\]\[0\]\['positions'\]: has dtype <U1"),
    ("positions NaN", _set(["meshes", 0, "positions", 5], [np.nan, 0, 0]),
     r"scene\['meshes'\]\[0\]\['positions'\]: row 5 has nan"),
    ("triangles float", _set(["meshes", 0, "triangles"], np.zeros((2, 3), np.float32)),
     r"scene\['meshes'\]\[0\]\['triangles'\]: has dtype float32; expected an integer array"),
    ("triangles range", _set(["meshes", 0, "triangles", 3, 1], 10_000),
     r"scene\['meshes'\]\[0\]\['triangles'\]: index 10000 out of range \[0, 266\) \(row 3\)"),
    # Indices are read as int32 (Blender's type, used in place); wider ones must fit, not wrap.
    ("triangles past 32 bits", _set(["meshes", 0, "triangles"], np.where(np.arange(3) == 1, 2**40 + 1, uv_sphere()[1])),
     r"scene\['meshes'\]\[0\]\['triangles'\]: has index 1099511627777, outside the 32-bit range"),
    ("uint64 indices past 32 bits", _set(["meshes", 0, "uv_indices"], np.full((N_TRI, 3), 2**63, np.uint64)),
     r"scene\['meshes'\]\[0\]\['uv_indices'\]: has index 9223372036854775808, outside the 32-bit range"),
    ("normal index range", _set(["meshes", 0, "normal_indices", 7, 2], 266),
     r"scene\['meshes'\]\[0\]\['normal_indices'\]: index 266 out of range \[0, 266\) \(row 7\)"),
    ("normal_indices rows", _set(["meshes", 0, "normal_indices"], np.zeros((3, 3), np.int32)),
     rf"scene\['meshes'\]\[0\]\['normal_indices'\]: has shape \(3, 3\); expected an integer array of shape \({N_TRI}, 3\)"),
    ("normals without indices", _set(["meshes", 0, "normal_indices"], KeyError),
     r"scene\['meshes'\]\[0\]\['normal_indices'\]: is missing while 'normals' is given"),
    ("uv NaN", _set(["meshes", 0, "uvs", 2], [np.inf, 0]), r"scene\['meshes'\]\[0\]\['uvs'\]: row 2 has inf"),
    ("material index range", _set(["meshes", 0, "material_indices", 4], 1),
     r"scene\['meshes'\]\[0\]\['material_indices'\]: index 1 out of range \[-1, 1\) \(row 4\)"),
    ("meshes not a list", _set(["meshes"], {"a": 1}), r"scene\['meshes'\]: is a dict; expected a list"),
    ("material unknown model", _set(["materials", 0, "model"], "velvet"), r"scene\['materials'\]\[0\]: .*velvet"),
    ("material bad param", _set(["materials", 0, "params"], {"reflectance": 2.0}),
     r"scene\['materials'\]\[0\]: .*reflectance"),
    ("material empty", _set(["materials", 0], {"name": "x"}), r"scene\['materials'\]\[0\]: has neither"),
    ("light type", _set(["lights", 0, "type"], "laser"), r"scene\['lights'\]\[0\]\['type'\]: unknown light type 'laser'"),
    ("light intensity missing", _set(["lights", 0, "intensity"], KeyError),
     r"scene\['lights'\]\[0\]\['intensity'\]: is missing; expected an RGB radiant intensity"),
    ("light intensity negative", _set(["lights", 0, "intensity"], [1, -1, 1]),
     r"scene\['lights'\]\[0\]\['intensity'\]: has -1.0; expected three numbers in \[0, inf\)"),
    ("light position NaN", _set(["lights", 0, "position"], [0, np.nan, 0]), r"scene\['lights'\]\[0\]\['position'\]: has nan"),
    ("spot size", _set(["lights", 0], {"type": "spot", "position": [0, 0, 3], "direction": [0, 0, -1],
                                       "intensity": [1, 1, 1], "spot_size": 4.0, "spot_blend": 0.1}),
     r"scene\['lights'\]\[0\]\['spot_size'\]: 4.0 is out of range; expected a number in \(0, pi\]"),
    ("sun zero direction", _set(["lights", 0], {"type": "sun", "direction": [0, 0, 0], "irradiance": [1, 1, 1]}),
     r"scene\['lights'\]\[0\]: .*direction"),
    ("area shape", _set(["lights", 0], {"type": "area", "shape": "star", "size": (1, 1), "matrix": np.eye(4),
                                        "power": 1.0, "color": [1, 1, 1]}),
     r"scene\['lights'\]\[0\]\['shape'\]: unknown area light shape 'star'"),
    ("instance without matrix", _set(["instance_mesh"], np.array([0])),
     r"scene\['instance_matrix'\]: is missing while 'instance_mesh' is given"),
    ("world colour", _set(["world", "color"], [1, 2]), r"scene\['world'\]\['color'\]: has shape \(2,\)"),
]


@pytest.mark.parametrize("edit,message", [b[1:] for b in BAD_SCENES], ids=[b[0] for b in BAD_SCENES])
def test_bad_scene_names_the_field(edit, message):
    scene = good_scene()
    if edit is None:
        scene = [scene]
    else:
        edit(scene)
    with pytest.raises(ValueError, match=message):
        bxdf.render(scene, DIRECT)


def test_bad_instances_name_the_field():
    scene = good_scene()
    scene["instance_mesh"] = np.array([0, 1], dtype=np.int32)
    scene["instance_matrix"] = np.stack([np.eye(4)] * 2)
    with pytest.raises(ValueError, match=r"scene\['instance_mesh'\]: index 1 out of range \[0, 1\) \(row 1\)"):
        bxdf.render(scene, DIRECT)
    scene["instance_mesh"] = np.array([0, 0], dtype=np.int32)
    scene["instance_matrix"] = np.stack([np.eye(4)] * 3)
    with pytest.raises(ValueError, match=r"scene\['instance_matrix'\]: has shape \(3, 4, 4\); expected a real array of shape \(2, 4, 4\)"):
        bxdf.render(scene, DIRECT)
    projective = np.stack([np.eye(4)] * 2)
    projective[1, 3, 2] = 0.5
    scene["instance_matrix"] = projective
    with pytest.raises(ValueError, match=r"scene\['instance_matrix'\]\[1\]: has last row"):
        bxdf.render(scene, DIRECT)
    far = np.stack([np.eye(4)] * 2)
    far[1, 1, 3] = 1e12  # past the renderer's coordinate range
    scene["instance_matrix"] = far
    with pytest.raises(ValueError, match=r"scene\['instance_matrix'\]\[1\]: has 1000000000000\.0; "
                                         r"expected entries in \[-1e9, 1e9\]"):
        bxdf.render(scene, DIRECT)
    nan = np.stack([np.eye(4)] * 2)
    nan[0, 2, 2] = np.nan
    scene["instance_matrix"] = nan
    with pytest.raises(ValueError, match=r"scene\['instance_matrix'\]\[0\]: has nan; expected a finite 4x4 matrix"):
        bxdf.render(scene, DIRECT)
    scene["instance_mesh"] = np.array([0.0, 0.0])
    scene["instance_matrix"] = np.stack([np.eye(4)] * 2)
    with pytest.raises(ValueError, match=r"scene\['instance_mesh'\]: has dtype float64; expected an integer array"):
        bxdf.render(scene, DIRECT)


BAD_SETTINGS = [
    ({"samples": 0}, r"settings\['samples'\]: 0 is out of range; expected an integer in \[1, "),
    ({"samples": 2.5}, r"settings\['samples'\]: 2.5 is not an integer"),
    ({"max_bounces": -1}, r"settings\['max_bounces'\]"),
    ({"transparent_max_bounces": 1025}, r"settings\['transparent_max_bounces'\]: 1025 is out of range; expected an integer in \[0, 1024\]"),
    ({"pixel_filter": "mitchell"}, r"settings\['pixel_filter'\]: 'mitchell' is unknown; expected 'box', 'gaussian', 'blackman_harris' or 'pixel_center'"),
    ({"filter_width": 0.0}, r"settings\['filter_width'\]: 0.0 is out of range; expected a number in \(0, 16\]"),
    ({"filter_width": float("nan")}, r"settings\['filter_width'\]"),
    ({"threads": -2}, r"settings\['threads'\]"),
    ({"seed": "x"}, r"settings\['seed'\]: 'x' is not an integer"),
    ({"spp": 4}, r"settings\['spp'\]: is not a setting; expected one of 'samples'"),
    ({"region": (0, 0, 4)}, r"settings\['region'\]: \(0, 0, 4\) is not 4 integers; expected None or"),
    ({"region": "0 0 4 4"}, r"settings\['region'\]: '0 0 4 4' is not 4 integers"),
    ({"region": (0, 0, 4.5, 4)}, r"settings\['region'\]\[2\]: 4.5 is not an integer"),
    ({"region": (4, 0, 4, 8)}, r"render setting 'region' is \(4, 0, 4, 8\); valid: \(x_min, y_min, "
                               r"x_max, y_max\) with 0 <= x_min < x_max <= width 24 and 0 <= y_min < "
                               r"y_max <= height 24 \(rows from the top\)"),
    ({"region": (0, 0, 25, 8)}, r"render setting 'region' is \(0, 0, 25, 8\)"),
    ([1, 2], r"settings: is a list; expected a dict"),
    ({"progressive": 1}, r"settings\['progressive'\]: 1 is not a bool; expected True or False"),
    ({"progressive": True, "samples_per_pass": 2}, r"samples_per_pass.*2.*0 with progressive passes"),
    ({"adaptive_sampling": "yes"}, r"settings\['adaptive_sampling'\]: 'yes' is not a bool"),
    ({"adaptive_threshold": 1.5}, r"settings\['adaptive_threshold'\]: 1.5 is out of range; expected a "
                                  r"number in \[0, 1\] \(0 = automatic\)"),
    ({"adaptive_threshold": -0.01}, r"settings\['adaptive_threshold'\]"),
    ({"adaptive_min_samples": 5000}, r"settings\['adaptive_min_samples'\]: 5000 is out of range"),
]


@pytest.mark.parametrize("settings,message", BAD_SETTINGS, ids=[str(s[0]) for s in BAD_SETTINGS])
def test_bad_settings_name_the_field(settings, message):
    with pytest.raises(ValueError, match=message):
        bxdf.render(good_scene(), settings)


def test_progressive_passes_start_with_one_sample_and_give_the_same_image():
    # The viewport's passes: a partial image after the first sample, then passes sized by time
    # (0.1 s at first); tile progress counts tile-samples and ends at its total.
    material = {"name": "m", "model": "lambertian", "params": {"reflectance": 0.5}}
    settings = dict(BIG, samples=16, tile_size=8)
    del settings["samples_per_pass"]
    expected = bxdf.render(scene_dict(material), settings)
    calls = []
    image, stats = bxdf.render(scene_dict(material), dict(settings, progressive=True),
                               lambda done, total, img: calls.append((done, total, img)),
                               return_stats=True)
    np.testing.assert_array_equal(image, expected)
    assert stats["samples_per_pixel"] == 16
    partial = [img for _, _, img in calls if img is not None]
    assert 1 <= len(partial) < 15  # not a pass per sample
    assert {total for _, total, _ in calls} == {16 * 9} and calls[-1][0] == 16 * 9


def test_adaptive_sampling_stops_converged_pixels_and_says_so():
    # A grey world seen past a lit sphere: the world's pixels agree with their half means at
    # once, the sphere's edge does not. Pixels still sampled at the end are the plain render's.
    material = {"name": "m", "model": "lambertian", "params": {"reflectance": 0.5}}
    scene = scene_dict(material)
    scene["world"] = {"color": [0.2, 0.2, 0.2]}
    settings = dict(BIG, samples=128, max_bounces=2, tile_size=8)
    del settings["samples_per_pass"]
    plain, plain_stats = bxdf.render(scene, settings, return_stats=True)
    adaptive = dict(settings, adaptive_sampling=True, adaptive_threshold=0.02, adaptive_min_samples=16)
    calls = []
    image, stats = bxdf.render(scene, adaptive, lambda done, total, img: calls.append((done, total)),
                               return_stats=True)
    assert stats["camera_samples"] < plain_stats["camera_samples"]
    assert not stats["cancelled"] and not plain_stats["converged"]
    assert calls[-1][0] == calls[-1][1]  # progress ends complete, converged early or not
    assert np.isfinite(image).all()
    same = np.all(image == plain, axis=2)
    assert same.any() and not same.all()
    assert np.abs(image[..., :3] - plain[..., :3]).mean() < 0.02 * plain[..., :3].mean()
    # A constant image stops every pixel at the first check, 64 + 1 | 15 = 79: 80 samples.
    world_only = {"meshes": [], "materials": [], "lights": [], "camera": scene["camera"],
                  "world": {"color": [0.3, 0.3, 0.3]}, "resolution": (SIZE, SIZE)}
    image, stats = bxdf.render(world_only, dict(settings, samples=256, adaptive_sampling=True),
                               return_stats=True)
    assert stats["converged"] and not stats["cancelled"]
    assert stats["samples_per_pixel"] == 80 and stats["camera_samples"] == 80 * SIZE * SIZE
    np.testing.assert_allclose(image[..., :3], 0.3, rtol=1e-6)


def test_a_region_renders_its_pixels_as_the_whole_image_does():
    # Blender's Render Region: only those pixels, each the whole render's (same seeds, same
    # camera rays), in an image of the region's size; the partial images are the region's too.
    material = {"name": "m", "model": "lambertian", "params": {"reflectance": 0.5}}
    scene = scene_dict(material)
    scene["world"] = {"color": [0.2, 0.3, 0.4]}
    settings = dict(BIG, samples=4, max_bounces=2, pixel_filter="gaussian", tile_size=8)
    whole = bxdf.render(scene, settings)
    region = (3, 5, 21, 16)  # x_min, y_min (rows from the top), x_max, y_max: exclusive
    partial = []
    part = bxdf.render(scene, dict(settings, region=region),
                       lambda done, total, img: partial.append((total, img)))
    assert part.shape == (11, 18, 4)
    np.testing.assert_array_equal(part, whole[5:16, 3:21])
    assert part[..., :3].max() > 0.01 and not np.array_equal(part[0], part[-1])
    np.testing.assert_array_equal(
        bxdf.render(scene, dict(settings, region=region), bottom_up=True), part[::-1])
    images = [img for _, img in partial if img is not None]
    assert images and all(img.shape == part.shape for img in images)
    assert {total for total, _ in partial} == {4 * 3 * 2}  # 4 passes of 3 x 2 tiles of 8
    # The whole image as a region, and None, are the whole render.
    np.testing.assert_array_equal(bxdf.render(scene, dict(settings, region=(0, 0, SIZE, SIZE))), whole)
    np.testing.assert_array_equal(bxdf.render(scene, dict(settings, region=None)), whole)


def test_filter_spellings_of_the_addon_accepted():
    for name in ("BOX", "GAUSSIAN", "BLACKMAN_HARRIS", "PIXEL_CENTER", "box", "gaussian",
                 "blackman_harris", "pixel_center"):
        image = bxdf.render(good_scene(), {"samples": 1, "max_bounces": 0, "pixel_filter": name})
        assert image.shape == (SIZE, SIZE, 4)


def test_ctrl_c_stops_the_render_and_raises_keyboard_interrupt():
    import os
    import signal

    scene = long_scene()
    timer = threading.Timer(0.05, os.kill, (os.getpid(), signal.SIGINT))
    started = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            bxdf.render(scene, LONG)
    finally:
        timer.cancel()
    assert time.perf_counter() - started < 1.0


def test_empty_scene_shows_the_world():
    scene = good_scene()
    scene["meshes"] = []
    scene["world"] = {"color": [0.25, 0.5, 1.0]}
    image = bxdf.render(scene, {"samples": 2, "max_bounces": 0})
    np.testing.assert_allclose(image[..., :3], np.broadcast_to([0.25, 0.5, 1.0], (SIZE, SIZE, 3)), rtol=1e-6)
