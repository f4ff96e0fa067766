"""Scene export (depsgraph → dict of numpy arrays), checked on a small hand-built scene."""

import math

import bpy
import numpy as np
import pytest

from bxdf_lab import api, export

CUBE_VERTS = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
CUBE_FACES = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]


def _object(name, verts, faces, collection):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    obj = bpy.data.objects.new(name, mesh)
    collection.objects.link(obj)
    return obj


def _material(name, model, **params):
    material = bpy.data.materials.new(name)
    api.assign(material, model, **params)
    return material


@pytest.fixture
def scene():
    scene = bpy.context.scene
    root = scene.collection
    red = _material("red", "lambertian", reflectance=(0.8, 0.1, 0.1))
    blue = _material("blue", "lambertian", reflectance=(0.1, 0.1, 0.8))

    plane = _object("plane", [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], [(0, 1, 2, 3)], root)
    plane.data.uv_layers.new(name="UVMap")
    plane.data.polygons[0].use_smooth = True
    plane.data.materials.append(red)

    # The cube lives in its own collection, instanced once more by an empty at x = 5.
    cubes = bpy.data.collections.new("cubes")
    root.children.link(cubes)
    cube = _object("cube", CUBE_VERTS, CUBE_FACES, cubes)
    cube.data.materials.append(red)
    cube.data.materials.append(blue)
    cube.data.polygons[1].material_index = 1  # the +x face
    cube.location = (0, 0, 3)
    empty = bpy.data.objects.new("instancer", None)
    empty.instance_type = "COLLECTION"
    empty.instance_collection = cubes
    empty.location = (5, 0, 0)
    root.objects.link(empty)

    for kind, energy in (("POINT", 100.0), ("SUN", 3.0), ("AREA", 50.0)):
        light = bpy.data.lights.new(kind.lower(), kind)
        light.energy = energy
        light.color = (1.0, 0.5, 0.25)
        if kind == "AREA":
            light.shape, light.size, light.size_y = "RECTANGLE", 2.0, 0.5
        obj = bpy.data.objects.new(kind.lower(), light)
        obj.location = (0, 0, 10)
        root.objects.link(obj)

    cam = bpy.data.cameras.new("cam")
    cam.lens, cam.sensor_width, cam.sensor_fit = 35.0, 32.0, "HORIZONTAL"
    cam.shift_x, cam.clip_start, cam.clip_end = 0.1, 0.05, 200.0
    cam_obj = bpy.data.objects.new("cam", cam)
    cam_obj.location = (0, -10, 5)
    root.objects.link(cam_obj)
    scene.camera = cam_obj
    scene.render.resolution_x, scene.render.resolution_y = 320, 240
    scene.render.resolution_percentage = 50

    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (0.2, 0.3, 0.4, 1.0)
    background.inputs["Strength"].default_value = 2.0
    scene.world = world
    return scene


def _export():
    return export.export_scene(bpy.context.evaluated_depsgraph_get())


def test_meshes_and_instances(scene):
    data = _export()
    names = [m["name"] for m in data["meshes"]]
    assert sorted(names) == ["cube", "plane"]  # the instanced cube shares the cube's mesh
    cube = data["meshes"][names.index("cube")]
    plane = data["meshes"][names.index("plane")]
    assert cube["positions"].dtype == np.float32 and cube["positions"].shape == (8, 3)
    assert cube["triangles"].dtype == np.int32 and cube["triangles"].shape == (12, 3)
    assert cube["normal_indices"] is None and cube["uvs"] is None  # all flat: no normals
    assert plane["uvs"].shape == (4, 2) and plane["uvs"].dtype == np.float32
    assert plane["uv_indices"].shape == (2, 3)
    corner_uvs = plane["uvs"][plane["uv_indices"]]  # Blender's default UVs: u = x, v = y mapped to [0, 1]
    np.testing.assert_allclose(corner_uvs, (plane["positions"][plane["triangles"]][:, :, :2] + 1) / 2,
                               atol=1e-6)
    # instances: plane, cube, and the cube again at x = 5 (+3 in z from the cube itself)
    cube_index = names.index("cube")
    cube_matrices = data["instance_matrix"][data["instance_mesh"] == cube_index]
    assert len(data["instance_mesh"]) == 3 and len(cube_matrices) == 2
    offsets = sorted(tuple(m[:3, 3]) for m in cube_matrices)
    assert offsets == [pytest.approx((0, 0, 3)), pytest.approx((5, 0, 3))]


def test_flat_meshes_leave_normals_to_the_triangles_and_smooth_faces_keep_vertex_normals(scene):
    data = _export()
    cube = next(m for m in data["meshes"] if m["name"] == "cube")
    assert cube["normals"] is None and cube["normal_indices"] is None
    plane = next(m for m in data["meshes"] if m["name"] == "plane")
    np.testing.assert_allclose(plane["normals"][plane["normal_indices"]].reshape(-1, 3),
                               [[0, 0, 1]] * 6, atol=1e-6)


def _corner_normals(data):
    return data["normals"][data["normal_indices"]]


def _blender_triangles(mesh):
    """Blender's own triangulation and split normals, for comparison."""
    mesh.calc_loop_triangles()
    mesh.calc_normals_split()
    loops = np.array([t.loops[:] for t in mesh.loop_triangles])
    vertices = np.array([t.vertices[:] for t in mesh.loop_triangles])
    normals = np.array([[mesh.loops[i].normal[:] for i in tri] for tri in loops])
    return vertices, normals


def test_triangles_and_normals_match_blenders_own_for_every_shading_case():
    # a non-planar quad, a triangle, a flat quad and (second mesh) a concave pentagon
    verts = [(0, 0, 0), (2, 0, 0.5), (2, 2, 0), (0, 2, 0.3), (3, 0, 0), (3, 1, 0.2),
             (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    faces = [(0, 1, 2, 3), (1, 4, 5), (6, 7, 8, 9)]
    pentagon = ([(0, 0, 0), (2, 0, 0), (2, 2, 0), (1, 0.5, 0), (0, 2, 0)], [(0, 1, 2, 3, 4)])
    for name, (v, f) in {"quads": (verts, faces), "ngon": pentagon}.items():
        mesh = bpy.data.meshes.new(name)
        mesh.from_pydata(v, [], f)
        for case in ("flat", "smooth", "mixed", "auto_smooth"):
            for i, polygon in enumerate(mesh.polygons):
                polygon.use_smooth = case in ("smooth", "auto_smooth") or (case == "mixed" and i % 2 == 0)
            mesh.use_auto_smooth = case == "auto_smooth"
            data = export.mesh_arrays(mesh)
            vertices, normals = _blender_triangles(mesh)
            np.testing.assert_array_equal(data["triangles"], vertices, err_msg=f"{name} {case}")
            if case == "flat":  # each triangle's own normal, as Cycles shades flat faces
                assert data["normals"] is None and data["normal_indices"] is None
                continue
            np.testing.assert_allclose(_corner_normals(data), normals, atol=1e-6, err_msg=f"{name} {case}")


def test_meshes_are_read_in_place_where_reading_changes_nothing_and_equal_a_copy():
    """A mesh object's evaluated mesh is read as it is (its cached normals kept, as Cycles reads
    it); auto smooth, custom normals and non-mesh objects go through a to_mesh() copy. Either
    way the arrays are those of the copy, modifiers applied."""
    collection = bpy.context.scene.collection
    ngon = _object("ngon_in_place", [(0, 0, 0), (2, 0, 0), (2, 2, 0), (1, 0.5, 0), (0, 2, 0)],
                   [(0, 1, 2, 3, 4)], collection)
    subdivided = _object("subsurf_in_place", CUBE_VERTS, CUBE_FACES, collection)
    subdivided.modifiers.new("subsurf", "SUBSURF").levels = 2
    for polygon in subdivided.data.polygons:
        polygon.use_smooth = polygon.index % 2 == 0
    auto_smooth = _object("auto_smooth_copied", CUBE_VERTS, CUBE_FACES, collection)
    auto_smooth.data.use_auto_smooth = True
    curve_data = bpy.data.curves.new("text_copied", "FONT")
    text = bpy.data.objects.new("text_copied", curve_data)
    collection.objects.link(text)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    nodes = export.node_materials.NodeMaterials()
    expected_copy = {"ngon_in_place": False, "subsurf_in_place": False,
                     "auto_smooth_copied": True, "text_copied": True}
    try:
        for name, copied_expected in expected_copy.items():
            evaluated = bpy.data.objects[name].evaluated_get(depsgraph)
            copy = evaluated.to_mesh()
            reference = export.mesh_arrays(copy)
            evaluated.to_mesh_clear()
            mesh, copied = export._readable_mesh(evaluated, [], nodes)
            try:
                assert copied == copied_expected, name
                got = export.mesh_arrays(mesh)
            finally:
                if copied:
                    evaluated.to_mesh_clear()
            for key, value in reference.items():
                if value is None:
                    assert got[key] is None, (name, key)
                else:
                    np.testing.assert_array_equal(got[key], value, err_msg=f"{name} {key}")
        subsurf = bpy.data.objects["subsurf_in_place"].evaluated_get(depsgraph)
        assert len(export._readable_mesh(subsurf, [], nodes)[0].polygons) == 6 * 16  # modifiers applied
    finally:
        for name in expected_copy:
            bpy.data.objects.remove(bpy.data.objects[name])


def test_an_object_in_edit_mode_is_read_from_a_copy():
    """Its evaluated mesh says it is in edit mode (Cycles copies it too, so that its layers are
    filled); the arrays are the copy's."""
    obj = _object("edited_cube", CUBE_VERTS, CUBE_FACES, bpy.context.scene.collection)
    bpy.context.view_layer.objects.active = obj
    bpy.ops.object.mode_set(mode="EDIT")
    try:
        evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
        reference = export.mesh_arrays(evaluated.to_mesh())
        evaluated.to_mesh_clear()
        mesh, copied = export._readable_mesh(evaluated, [], export.node_materials.NodeMaterials())
        try:
            assert copied
            np.testing.assert_array_equal(export.mesh_arrays(mesh)["triangles"], reference["triangles"])
        finally:
            evaluated.to_mesh_clear()
    finally:
        bpy.ops.object.mode_set(mode="OBJECT")
        bpy.data.objects.remove(obj)


def test_material_indices_point_into_the_scene_material_table(scene):
    data = _export()
    table = [m["name"] for m in data["materials"]]
    assert sorted(table) == ["blue", "red"]
    assert data["materials"][table.index("red")]["model"] == "lambertian"
    assert data["materials"][table.index("red")]["params"]["reflectance"] == pytest.approx((0.8, 0.1, 0.1))
    cube = next(m for m in data["meshes"] if m["name"] == "cube")
    p = cube["positions"][cube["triangles"]]
    on_plus_x = np.all(np.isclose(p[:, :, 0], 1.0), axis=1)
    assert on_plus_x.sum() == 2
    assert set(cube["material_indices"][on_plus_x]) == {table.index("blue")}
    assert set(cube["material_indices"][~on_plus_x]) == {table.index("red")}


def test_lights_in_blender_units(scene):
    lights = {l["type"]: l for l in _export()["lights"]}
    color = np.array([1.0, 0.5, 0.25])
    point = lights["point"]
    np.testing.assert_allclose(point["intensity"], 100.0 * color / (4 * math.pi), rtol=1e-6)
    np.testing.assert_allclose(point["position"], (0, 0, 10))
    np.testing.assert_allclose(point["direction"], (0, 0, -1), atol=1e-7)
    np.testing.assert_allclose(lights["sun"]["irradiance"], 3.0 * color, rtol=1e-6)
    area = lights["area"]
    assert area["power"] == pytest.approx(50.0) and area["size"] == pytest.approx((2.0, 0.5))
    assert area["shape"] == "rectangle"
    np.testing.assert_allclose(area["color"], color, rtol=1e-6)
    # Lights are hidden from camera rays unless their object says otherwise, as in Cycles.
    assert all(not l["visible_camera"] and l["cast_shadow"] and l["use_mis"] for l in lights.values())


def test_camera_resolution_and_world(scene):
    data = _export()
    camera = data["camera"]
    assert data["resolution"] == camera["resolution"] == (160, 120)
    assert (camera["lens"], camera["sensor_width"], camera["sensor_fit"]) == (35.0, 32.0, "horizontal")
    assert camera["shift"] == pytest.approx((0.1, 0.0)) and camera["clip"] == pytest.approx((0.05, 200.0))
    np.testing.assert_allclose(camera["matrix"][:3, 3], (0, -10, 5))
    np.testing.assert_allclose(data["world"]["color"], (0.4, 0.6, 0.8), rtol=1e-6)
    assert data["warnings"] == []


def test_an_object_that_is_not_a_camera_as_the_scene_camera_gives_cycles_default_camera(scene):
    scene.camera = bpy.data.objects["instancer"]
    data = _export()
    camera = data["camera"]
    assert (camera["lens"], camera["sensor_width"], camera["sensor_fit"]) == (50.0, 36.0, "auto")
    np.testing.assert_allclose(camera["matrix"][:3, 3], (5, 0, 0))
    assert "scene camera 'instancer' is an object of type EMPTY" in camera["warning"]
    assert data["warnings"] == []  # the viewport, which shares the export, has its own camera


def test_an_unsupported_world_texture_becomes_the_socket_default_with_a_warning(scene):
    tree = scene.world.node_tree
    sky = tree.nodes.new("ShaderNodeTexSky")
    background = tree.nodes["Background"]
    tree.links.new(sky.outputs["Color"], background.inputs["Color"])
    background.inputs["Color"].default_value = (0.1, 0.2, 0.3, 1.0)
    background.inputs["Strength"].default_value = 2.0
    data = _export()
    np.testing.assert_allclose(data["world"]["color"], (0.2, 0.4, 0.6), rtol=1e-6)
    assert len(data["warnings"]) == 1
    assert "world 'world'" in data["warnings"][0] and sky.name in data["warnings"][0]


def test_transparent_glass_film_is_named_as_unsupported(scene):
    scene.render.film_transparent = True
    assert _export()["warnings"] == []
    scene.cycles.film_transparent_glass = True
    warnings = _export()["warnings"]
    assert len(warnings) == 1 and "Transparent Glass" in warnings[0]


def test_a_broken_material_is_refused_naming_it(scene):
    bpy.data.materials["blue"].bxdf_lab.lambertian.reflectance = (0.5, float("nan"), 0.5)
    with pytest.raises(ValueError, match="blue.*reflectance"):
        _export()
