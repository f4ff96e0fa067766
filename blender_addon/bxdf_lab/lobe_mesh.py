"""A 3D polar plot of a reflection lobe as a Blender mesh object (geometry from bxdf.lobe_mesh:
the vertex for direction ωi is ωi·luminance(f(ωo, ωi)·|cos θi|)), scaled so that the longest
radius is `size`."""

import bpy
import numpy as np

from . import dependency
from .bake import hemisphere


def lobe_geometry(model, theta_in_deg, resolution=32, size=1.0):
    """(vertices (V, 3) float32, triangles (T, 3) int32), longest radius `size`."""
    vertices, triangles = dependency.require().lobe_mesh(model, resolution=resolution,
                                                         theta_o=float(theta_in_deg),
                                                         hemisphere=hemisphere(model))
    vertices = np.asarray(vertices, dtype=np.float32)
    longest = float(np.linalg.norm(vertices, axis=1).max()) if len(vertices) else 0.0
    if longest > 0.0:
        vertices = vertices * (size / longest)
    return vertices, np.asarray(triangles, dtype=np.int32)


def add_lobe_object(context, model, name, theta_in_deg, size=1.0):
    vertices, triangles = lobe_geometry(model, theta_in_deg, size=size)
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(vertices))
    mesh.vertices.foreach_set("co", vertices.ravel())
    mesh.loops.add(triangles.size)
    mesh.loops.foreach_set("vertex_index", triangles.ravel())
    mesh.polygons.add(len(triangles))
    mesh.polygons.foreach_set("loop_start", np.arange(0, triangles.size, 3, dtype=np.int32))
    mesh.polygons.foreach_set("loop_total", np.full(len(triangles), 3, dtype=np.int32))
    mesh.update()
    mesh.validate()
    obj = bpy.data.objects.new(name, mesh)
    context.collection.objects.link(obj)
    return obj
