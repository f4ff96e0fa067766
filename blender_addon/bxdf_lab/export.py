"""Blender scene → plain data for the renderer: a dict of numpy arrays and small dicts.

Everything leaves Blender through `foreach_get` into numpy arrays of the matching dtype (index
properties into uint32, their type in Blender 3.4, then viewed as int32; never raw pointers:
Blender's mesh layout changes between versions). The result has no bpy objects in it, so it can
be tested, pickled, or handed to the renderer's binding unchanged.

    {
      "meshes": [{"name": str,
                  "positions": (V, 3) float32, object space,
                  "triangles": (T, 3) int32 indices into positions,
                  "normals": (N, 3) float32 and "normal_indices": (T, 3) int32: the shading
                      normal at corner k of triangle t is normals[normal_indices[t, k]] (smooth,
                      flat, auto-smooth or custom normals, as Blender shades them); both None
                      when every face is flat (each triangle shaded with its own normal),
                  "uvs": (U, 2) float32 and "uv_indices": (T, 3) int32, or both None without a
                      UV map,
                  "material_indices": (T,) int32 into "materials", -1 = no material}],
      "instance_mesh": (I,) int32 into "meshes", "instance_matrix": (I, 4, 4) float32 object→world,
      "materials": [{"name", "model", "params", "flags"}],  # bxdf.make(model, **params); a
                  # material rendered from its node tree: {"name", "graph"} (node_materials.py)
      "lights": [{"type", "name", "matrix", "position", "direction", "color", "power", ...}],
                  # light_export.py
      "camera": {...},  # camera_dict; "warning" when the scene camera is not a camera object
      "world": {"color", "texture", ...},  # world_export.py
      "resolution": (width, height), "film_transparent": bool,
      "warnings": [str],  # things exported approximately, each naming the world/light/material
    }

Each mesh also carries its object's "visible_camera", "visible_shadow" and "terminator_offset"
(Cycles' geometry and shading offsets).

A mesh is exported once however many objects show it: objects whose evaluated geometry is the
same (linked duplicates without modifiers, collection instances, geometry-nodes instances from
depsgraph.object_instances) with the same materials, visibility and offsets share one entry of
"meshes", and each adds only an instance (the renderer then stores the mesh once, see
bxdf.render). An object with modifiers has geometry of its own, as in Cycles.

Mesh attributes are indexed separately from positions (as in OBJ), so that a flat face or a UV
seam needs no duplicated vertices and a smooth mesh shares one normal per vertex.

Lights and their units: light_export.py. The world: world_export.py.
"""

import numpy as np

from . import api, array_pool, light_export, material_source, node_materials, world_export

# Mesh arrays come from the pool of the last export's arrays (array_pool.py: fresh memory is a
# page fault per 4 KB).
_pool = array_pool.mesh_arrays

GEOMETRY_TYPES = {"MESH", "CURVE", "SURFACE", "META", "FONT"}


def _matrix(m):
    return np.array(m, dtype=np.float32).reshape(4, 4)


def _fan_corners(loop_start, loop_total):
    """Loop indices (T, 3) and polygon index (T,) of each triangle of a mesh whose polygons are
    triangles and quads, in Blender's own order and split: a quad (0, 1, 2, 3) becomes
    (0, 1, 2), (0, 2, 3), as Blender's loop triangles do (checked by tests/blender/test_export.py).
    Written into one int32 array: each temporary of a triangle's length is fresh memory to fault
    in, which costs more than the arithmetic."""
    triangle_polygon = np.repeat(np.arange(len(loop_start), dtype=np.int32), loop_total - 2)
    corners = _pool.empty(len(triangle_polygon) * 3, np.int32).reshape(-1, 3)
    np.take(loop_start, triangle_polygon, out=corners[:, 0])
    np.add(corners[:, 0], 1, out=corners[:, 1])
    # A quad's second triangle (one after a triangle of the same polygon) starts at its corner 2.
    corners[1:, 1] += triangle_polygon[1:] == triangle_polygon[:-1]
    np.add(corners[:, 1], 1, out=corners[:, 2])
    return corners, triangle_polygon


def _indices(collection, prop, count):
    """An index property of every element (loops' vertex_index, polygons' loop_start, ...) as
    int32. Read into uint32, the type these properties have in Blender 3.4: foreach_get then
    copies without converting (the raw array of polygons and loops, 15x faster than into int32;
    loop triangles 3-6x), where an int32 buffer makes it convert element by element. Viewed as
    int32 without a copy (Blender's indices are below 2^31)."""
    out = _pool.empty(count, np.uint32)
    collection.foreach_get(prop, out)
    return out.view(np.int32)


def _loop_triangle_corners(mesh):
    """The general path for meshes with n-gons: Blender's own triangulation of each polygon
    (loop_triangles are not a raw array: slower per element than the polygon arrays)."""
    n_triangles = len(mesh.loop_triangles)
    corners = _indices(mesh.loop_triangles, "loops", n_triangles * 3)
    triangle_polygon = _indices(mesh.loop_triangles, "polygon_index", n_triangles)
    return corners.reshape(n_triangles, 3), triangle_polygon


def mesh_arrays(mesh):
    """Arrays of one evaluated Blender mesh (see the module docstring for the layout)."""
    n_vertices, n_polygons, n_loops = len(mesh.vertices), len(mesh.polygons), len(mesh.loops)
    positions = _pool.empty(n_vertices * 3, np.float32)
    mesh.vertices.foreach_get("co", positions)
    loop_vertex = _indices(mesh.loops, "vertex_index", n_loops)
    loop_start = _indices(mesh.polygons, "loop_start", n_polygons)
    loop_total = _indices(mesh.polygons, "loop_total", n_polygons)
    # Polygon arrays are raw memory (fast); loop_triangles go through RNA per element (about
    # 0.25 s per million triangles), so triangles and quads are split here and only n-gons use them.
    if n_polygons == 0 or loop_total.max() <= 4:
        corners, triangle_polygon = _fan_corners(loop_start, loop_total)
    else:
        mesh.calc_loop_triangles()
        corners, triangle_polygon = _loop_triangle_corners(mesh)
    # Blender's loops name valid vertices: "clip" clips nothing, and spares the copy of `out`
    # that np.take's default mode makes.
    triangles = np.take(loop_vertex, corners, out=_pool.empty(corners.size, np.int32).reshape(-1, 3),
                        mode="clip")

    polygon_material = _pool.zeros(n_polygons, np.int32)
    if "material_index" in mesh.attributes:  # absent: every polygon uses slot 0
        mesh.polygons.foreach_get("material_index", polygon_material)

    smooth = _pool.empty(n_polygons, bool)
    mesh.polygons.foreach_get("use_smooth", smooth)
    if mesh.has_custom_normals or mesh.use_auto_smooth:
        # Split normals honour auto smooth and custom normals; they are per loop.
        mesh.calc_normals_split()
        normals = _pool.empty(n_loops * 3, np.float32)
        mesh.loops.foreach_get("normal", normals)
        normals, normal_indices = normals.reshape(n_loops, 3), corners
    else:
        # Mesh.vertex_normals and polygon_normals read the normal arrays directly: 1.5x (2.4x
        # for polygons) quicker than the same numbers through MeshVertex.normal and
        # MeshPolygon.normal.
        vertex_normals = _pool.empty(n_vertices * 3, np.float32)
        mesh.vertex_normals.foreach_get("vector", vertex_normals)
        vertex_normals = vertex_normals.reshape(n_vertices, 3)
        if smooth.all():
            normals, normal_indices = vertex_normals, triangles
        else:
            polygon_normals = _pool.empty(n_polygons * 3, np.float32)
            mesh.polygon_normals.foreach_get("vector", polygon_normals)
            flat_index = (n_vertices + triangle_polygon)[:, None]
            if not smooth.any():
                # All flat: no normals at all. The renderer shades each triangle with its own
                # normal, as Cycles does for flat faces, and welding splits no vertex by normal
                # (a flat mesh stored with face normals per corner takes three times the memory).
                normals = normal_indices = None
            else:
                normals = np.concatenate([vertex_normals, polygon_normals.reshape(n_polygons, 3)])
                normal_indices = np.where(smooth[triangle_polygon][:, None], triangles, flat_index)

    uvs, uv_indices = None, None
    uv_layer = mesh.uv_layers.active
    if uv_layer is not None:
        uvs = _pool.empty(n_loops * 2, np.float32)
        uv_layer.data.foreach_get("uv", uvs)
        uvs, uv_indices = uvs.reshape(n_loops, 2), corners

    return {
        "positions": positions.reshape(n_vertices, 3),
        "triangles": triangles,
        "normals": normals,
        "normal_indices": None if normal_indices is None else np.ascontiguousarray(normal_indices, dtype=np.int32),
        "uvs": uvs,
        "uv_indices": uv_indices,
        "material_indices": np.take(polygon_material, triangle_polygon,
                                    out=_pool.empty(len(triangle_polygon), np.int32), mode="clip"),
    }


class _MaterialTable:
    """Materials in first-use order; each is validated once through the registry."""

    def __init__(self):
        self.index = {}
        self.entries = []
        self.nodes = node_materials.NodeMaterials()

    def get(self, material):
        if material is None:
            return -1
        material = material.original
        if material.name in self.index:
            return self.index[material.name]
        if material_source.source(material) == "NODES":
            self.index[material.name] = len(self.entries)
            self.entries.append(self.nodes.entry(material))
        else:
            self.nodes.count_for_cycles(material)
            model = api.make(material)  # ValueError naming the material on a bad value
            self.index[material.name] = len(self.entries)
            name, params = api.describe(material)
            self.entries.append({"name": material.name, "model": name, "params": params,
                                 "flags": set(getattr(model, "flags", ()))})
        return self.index[material.name]


def _readable_mesh(obj, slot_materials, nodes):
    """The mesh to export of an evaluated object and whether it is a temporary copy. A mesh
    object's own evaluated mesh is read in place, as Cycles reads it (blender/mesh.cpp): it keeps
    the normals the depsgraph computed, which a copy from to_mesh() recomputes (10 spheres of 16k
    triangles: 6.8 ms to read against 12.2 ms). A copy where reading would change it or where it
    is incomplete: split normals (auto smooth, custom normals), tangents for Normal Map nodes, an
    object in edit mode, and objects that are not meshes (curves, text, metaballs)."""
    mesh = obj.data if obj.type == "MESH" else None
    if (mesh is not None and not mesh.is_editmode and not mesh.use_auto_smooth
            and not mesh.has_custom_normals and not nodes.needs_tangents(slot_materials)):
        return mesh, False
    return obj.to_mesh(), True


def _object_mesh(obj, materials):
    """The mesh dict of an evaluated object, with material slots mapped to the scene table."""
    slots = [materials.get(slot.material) for slot in obj.material_slots]
    slot_materials = [slot.material and slot.material.original for slot in obj.material_slots]
    mesh, copied = _readable_mesh(obj, slot_materials, materials.nodes)
    try:
        if mesh is None:
            return None
        data = mesh_arrays(mesh)
        data.update(materials.nodes.mesh_attributes(mesh, data, slot_materials))
    finally:
        if copied:
            obj.to_mesh_clear()
    slot_of_triangle = data["material_indices"]
    scene_material = _pool.empty(len(slot_of_triangle), np.int32)
    if slots:
        # "clip": a slot past the last counts as the last, as in Blender.
        np.take(np.asarray(slots, dtype=np.int32), slot_of_triangle, out=scene_material, mode="clip")
    else:
        scene_material.fill(-1)
    data["material_indices"] = scene_material
    data["name"] = obj.name
    # Object ray visibility and Cycles' shadow terminator offsets (geometry, shading).
    data["visible_camera"] = bool(obj.visible_camera)
    data["visible_shadow"] = bool(obj.visible_shadow)
    cycles = getattr(obj, "cycles", None)
    data["terminator_offset"] = (float(getattr(cycles, "shadow_terminator_geometry_offset", 0.1)),
                                 min(float(getattr(cycles, "shadow_terminator_offset", 0.0)), 0.999))
    return data


def _shared_mesh_key(obj):
    """What decides whether two evaluated objects can share one exported mesh: the evaluated
    geometry itself (its address as an identity key, never read through: linked duplicates and
    instances point to the same evaluated data, a modified object to its own) and everything
    _object_mesh takes from the object rather than from the geometry."""
    slots = tuple(slot.material.original.name if slot.material else None for slot in obj.material_slots)
    cycles = getattr(obj, "cycles", None)
    offsets = (float(getattr(cycles, "shadow_terminator_geometry_offset", 0.1)),
               float(getattr(cycles, "shadow_terminator_offset", 0.0)))
    geometry = obj.data.as_pointer() if obj.data is not None else ("object", obj.name)
    return (obj.type, geometry, slots, bool(obj.visible_camera), bool(obj.visible_shadow), offsets)


def resolution(scene):
    r = scene.render
    return (int(r.resolution_x * r.resolution_percentage / 100),
            int(r.resolution_y * r.resolution_percentage / 100))


# Cycles' camera for a scene camera that is not a camera object (blender_camera_init): Blender
# lets any object be the scene camera, and Cycles then looks along its -Z with these settings.
_DEFAULT_CAMERA = {"type": "persp", "lens": 50.0, "sensor_width": 36.0, "sensor_height": 24.0,
                   "sensor_fit": "auto", "shift": (0.0, 0.0), "clip": (1e-5, 1e5), "ortho_scale": 1.0}
# A light's spot size when Python cannot read it: Blender's default (the field lives in every
# light's data, but only a spot light shows it).
_DEFAULT_SPOT_SIZE = np.radians(45.0)


def _object_camera(camera_obj):
    """Cycles' camera through a non-camera object (blender_camera_from_object): the defaults, with
    a light's spot size as the field of view (lens = 16 mm / tan(spot size / 2))."""
    settings = dict(_DEFAULT_CAMERA)
    how = "Cycles' default camera (50 mm lens, 36 mm sensor, automatic fit)"
    if camera_obj.type == "LIGHT":
        spot_size = float(getattr(camera_obj.data, "spot_size", _DEFAULT_SPOT_SIZE))
        settings["lens"] = 16.0 / np.tan(0.5 * spot_size)
        how = (f"a {settings['lens']:.1f} mm lens on a 36 mm sensor, the light's "
               f"{'spot size' if camera_obj.data.type == 'SPOT' else 'default spot size'} "
               f"of {np.degrees(spot_size):.0f}° as Cycles does")
    settings["warning"] = (f"scene camera '{camera_obj.name}' is an object of type {camera_obj.type}, "
                           f"not a camera: rendered through it with {how}")
    return settings


def camera_dict(scene, camera_obj):
    """Blender's camera model: lens and sensor (with fit), shift, clip, resolution, aspect. A
    scene camera that is not a camera object gives Cycles' camera through it, with a "warning"
    that a render through it reports (the viewport has a camera of its own)."""
    width, height = resolution(scene)
    r = scene.render
    out = {"resolution": (width, height),
           "pixel_aspect": float(r.pixel_aspect_y / r.pixel_aspect_x)}
    if camera_obj is None:
        out["missing"] = True
        return out
    matrix = _matrix(camera_obj.matrix_world)
    # Blender ignores scale for the view; the renderer wants an orthonormal frame.
    for axis in range(3):
        matrix[:3, axis] /= max(np.linalg.norm(matrix[:3, axis]), 1e-30)
    out.update({"name": camera_obj.name, "matrix": matrix})  # camera looks along -Z, +Y up
    if camera_obj.type != "CAMERA":
        out.update(_object_camera(camera_obj))
        return out
    cam = camera_obj.data
    out.update({
        "type": cam.type.lower(),
        "lens": float(cam.lens),  # mm
        "sensor_width": float(cam.sensor_width),
        "sensor_height": float(cam.sensor_height),
        "sensor_fit": cam.sensor_fit.lower(),  # auto, horizontal, vertical
        "shift": (float(cam.shift_x), float(cam.shift_y)),
        "clip": (float(cam.clip_start), float(cam.clip_end)),
        "ortho_scale": float(cam.ortho_scale),
    })
    return out


def export_scene(depsgraph):
    """The evaluated scene as plain data (see the module docstring). ValueError names a material
    whose stored parameters the registry refuses."""
    _pool.begin_export()
    scene = depsgraph.scene_eval
    materials = _MaterialTable()
    warnings = []
    meshes, mesh_index = [], {}
    instance_mesh, instance_matrix, lights = [], [], []
    for inst in depsgraph.object_instances:
        obj = inst.object
        if not inst.is_instance and not inst.show_self:
            continue
        if obj.type == "LIGHT":
            lights.append(light_export.light_dict(obj, inst.matrix_world, warnings))
            continue
        if obj.type not in GEOMETRY_TYPES:
            continue
        key = _shared_mesh_key(obj)
        if key not in mesh_index:
            data = _object_mesh(obj, materials)
            if data is None or len(data["triangles"]) == 0:
                mesh_index[key] = -1
            else:
                mesh_index[key] = len(meshes)
                meshes.append(data)
        if mesh_index[key] >= 0:
            instance_mesh.append(mesh_index[key])
            instance_matrix.append(_matrix(inst.matrix_world))

    # The original scene's settings: a Python-defined property edit (Cycles' own) does not
    # always reach the evaluated copy before the next depsgraph update.
    original = depsgraph.scene
    if original.render.film_transparent and getattr(getattr(original, "cycles", None),
                                                    "film_transparent_glass", False):
        warnings.append("Film: Transparent Glass is not supported; glass seen against the "
                        "background stays opaque in the alpha")
    data = {
        "meshes": meshes,
        "instance_mesh": np.asarray(instance_mesh, dtype=np.int32),
        "instance_matrix": (np.stack(instance_matrix) if instance_matrix
                            else np.zeros((0, 4, 4), dtype=np.float32)),
        "materials": materials.entries,
        "lights": lights,
        "camera": camera_dict(scene, scene.camera.evaluated_get(depsgraph) if scene.camera else None),
        "world": world_export.world_dict(scene.world, warnings),
        "film_transparent": bool(scene.render.film_transparent),
        "resolution": resolution(scene),
        "warnings": warnings,
    }
    materials.nodes.finish(data)
    return data
