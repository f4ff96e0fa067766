"""Mapping → `transform` with the 3×4 matrix Cycles' svm_mapping applies for the node's type
(Point: T·R·S; Texture: the inverse; Vector: R·S; Normal: R·S⁻¹ then normalised), Euler XYZ
rotation. Location, Rotation and Scale must be constants (a linked one is reported)."""

import mathutils
import numpy as np

from . import graph as g

BL_IDNAMES = ("ShaderNodeMapping",)


def _safe_inverse(scale):
    return np.array([1.0 / s if s != 0.0 else 0.0 for s in scale])


def matrix(vector_type, location, rotation, scale):
    """The 3×4 matrix (rows) of a Mapping node."""
    r = np.array(mathutils.Euler(rotation, "XYZ").to_matrix(), dtype=np.float64)
    s, loc = np.array(scale, dtype=np.float64), np.array(location, dtype=np.float64)
    if vector_type == "POINT":
        linear, offset = r * s[None, :], loc
    elif vector_type == "TEXTURE":
        linear = _safe_inverse(s)[:, None] * r.T
        offset = -linear @ loc
    elif vector_type == "VECTOR":
        linear, offset = r * s[None, :], np.zeros(3)
    else:  # NORMAL
        linear, offset = r * _safe_inverse(s)[None, :], np.zeros(3)
    return np.hstack([linear, offset[:, None]]).tolist()


def value(scope, node, output):
    parts = {}
    for name in ("Location", "Rotation", "Scale"):
        socket = scope.socket(name) if name in node.inputs else None
        if socket is None or not socket.enabled:
            parts[name] = (0.0, 0.0, 0.0)
            continue
        if scope.linked(name):
            scope.warn(f"a linked {name} is not translated; its default value "
                       f"{tuple(socket.default_value)} is used", status="unsupported")
        parts[name] = g.to_triple(tuple(socket.default_value))
    return scope.graph.add(
        "transform", ["vector"], vector=scope.input("Vector", "triple"),
        matrix=matrix(node.vector_type, parts["Location"], parts["Rotation"], parts["Scale"]),
        kind="point" if node.vector_type in ("POINT", "TEXTURE") else "vector",
        normalize=node.vector_type == "NORMAL")["vector"]
