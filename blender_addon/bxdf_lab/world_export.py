"""Blender's world → the renderer's world (plugin/include/bxdf/render/environment.h).

A small chain parser of its own: the renderer's world is radiance = color + weight·image(M·ω),
which covers what a user's world usually is — Background (colour × Strength), an Environment
Texture whose Vector comes from Texture Coordinate (Generated/Object) through Mapping, mixed with
a colour by Mix/MixRGB (mix, multiply, add), Mix Shader and Add Shader of Backgrounds. Anything
else is replaced (by the socket's default value, or the world's viewport colour) with a warning
that names the world and the node. The texture entry uses the fields of the material graph's
`image` textures and `transform` op (docs/material-graph.md): path, interpolation, colorspace,
and the 3×4 matrix of the Mapping node.

    {"color": (3,) float32, "texture": {"path", "weight": (3,), "matrix": (3, 4), "kind",
                                       "interpolation", "colorspace"} or absent,
     "sampling": "auto"|"manual"|"none", "map_resolution": int}
"""

import os

import bpy
import mathutils
import numpy as np


class _Unsupported(Exception):
    """A node or link the chain parser cannot translate; the message says what was used."""


class _Term:
    """color + weight·texture: the affine form every supported chain reduces to."""

    def __init__(self, color, weight=None, texture=None):
        self.color = np.asarray(color, dtype=np.float64)[:3]
        self.weight = np.zeros(3) if weight is None else np.asarray(weight, dtype=np.float64)[:3]
        self.texture = texture

    def scaled(self, s):
        return _Term(self.color * s, self.weight * s, self.texture)

    def plus(self, other):
        if self.texture is not None and other.texture is not None and self.texture is not other.texture:
            raise _Unsupported("two environment textures are combined; only one is supported")
        return _Term(self.color + other.color, self.weight + other.weight, self.texture or other.texture)


def _constant(socket):
    value = socket.default_value
    try:
        values = list(value)
    except TypeError:
        values = [float(value)] * 3
    return np.array((values + values[-1:] * 3)[:3], dtype=np.float64)


def _linked_from(socket):
    """The output socket feeding `socket`, skipping reroutes and muted links."""
    if not socket.is_linked:
        return None
    link = socket.links[0]
    if not link.is_valid or link.is_muted:
        return None
    out = link.from_socket
    while out.node.type == "REROUTE":
        inp = out.node.inputs[0]
        if not inp.is_linked:
            return None
        out = inp.links[0].from_socket
    return out


def _number(node, socket, warnings, world):
    if _linked_from(socket) is not None:
        warnings.append(f"world '{world.name}': node '{node.name}' ({node.type}) input "
                        f"'{socket.name}' is linked; its default value {socket.default_value:g} "
                        "was used (only constant factors and strengths are exported)")
    return float(socket.default_value)


def _mapping_matrix(node, warnings, world):
    """Blender's Mapping node as a 3×4 matrix acting on the texture vector (Cycles' svm_mapping)."""
    def vec(name):
        s = node.inputs.get(name)
        if s is None or not s.enabled:
            return None
        if _linked_from(s) is not None:
            warnings.append(f"world '{world.name}': Mapping '{node.name}' input '{name}' is linked; "
                            "its default value was used")
        return np.array(s.default_value[:3], dtype=np.float64)

    location = vec("Location")
    rotation = vec("Rotation")
    scale = vec("Scale")
    location = np.zeros(3) if location is None else location
    scale = np.ones(3) if scale is None else scale
    r = np.array(mathutils.Euler(rotation if rotation is not None else (0, 0, 0), "XYZ").to_matrix())
    safe_inv_scale = np.where(scale != 0.0, 1.0 / np.where(scale != 0.0, scale, 1.0), 0.0)
    kind = node.vector_type
    if kind == "POINT":
        m, offset = r @ np.diag(scale), location
    elif kind == "TEXTURE":
        m = np.diag(safe_inv_scale) @ r.T
        offset = -m @ location
    elif kind == "VECTOR":
        m, offset = r @ np.diag(scale), np.zeros(3)
    else:  # NORMAL: the environment lookup normalises the vector anyway
        m, offset = r @ np.diag(safe_inv_scale), np.zeros(3)
    return np.concatenate([m, offset[:, None]], axis=1)


def _vector_matrix(socket, warnings, world):
    """The 3×4 matrix giving the Environment Texture's Vector from the world direction."""
    identity = np.concatenate([np.eye(3), np.zeros((3, 1))], axis=1)
    out = _linked_from(socket)
    if out is None:
        return identity  # unlinked: the direction itself (Generated)
    node = out.node
    if node.type == "TEX_COORD":
        if out.name not in ("Generated", "Object"):
            raise _Unsupported(f"Texture Coordinate output '{out.name}' (only Generated and "
                               "Object, the world direction, are exported)")
        return identity
    if node.type == "MAPPING":
        return _mapping_matrix(node, warnings, world) @ np.vstack(
            [_vector_matrix(node.inputs["Vector"], warnings, world), [0, 0, 0, 1]])
    raise _Unsupported(f"node '{node.name}' ({node.type}) feeding the Vector input")


def _environment_texture(node, warnings, world):
    image = node.image
    if image is None:
        raise _Unsupported(f"Environment Texture '{node.name}' has no image")
    if node.projection != "EQUIRECTANGULAR":
        raise _Unsupported(f"Environment Texture '{node.name}' projection {node.projection} "
                           "(only Equirectangular)")
    if image.packed_file is not None or image.source != "FILE":
        raise _Unsupported(f"image '{image.name}' is packed or generated (only image files on disk)")
    path = bpy.path.abspath(image.filepath_raw or image.filepath, library=image.library)
    if not os.path.isfile(path):
        raise _Unsupported(f"image file '{path}' of '{image.name}' does not exist")
    interpolation = node.interpolation.lower()
    if interpolation not in ("linear", "closest"):
        warnings.append(f"world '{world.name}': Environment Texture '{node.name}' interpolation "
                        f"{node.interpolation} rendered as Linear")
        interpolation = "linear"
    colorspace = image.colorspace_settings.name
    is_float = path.lower().endswith((".exr", ".hdr"))
    if is_float and colorspace not in ("Linear", "Non-Color", "Raw"):
        warnings.append(f"world '{world.name}': image '{image.name}' colour space {colorspace} "
                        "ignored; the float image is read as linear")
    if not is_float and colorspace not in ("sRGB",):
        warnings.append(f"world '{world.name}': image '{image.name}' colour space {colorspace} "
                        "ignored; the 8-bit image is decoded from sRGB")
    return {"path": os.path.abspath(path),
            "matrix": _vector_matrix(node.inputs["Vector"], warnings, world),
            "kind": "point", "interpolation": interpolation,
            "colorspace": "linear" if is_float else "srgb"}


def _colour_term(socket, warnings, world, textures):
    """The colour arriving at `socket` as a _Term."""
    out = _linked_from(socket)
    if out is None:
        return _Term(_constant(socket))
    node = out.node
    if node.type == "TEX_ENVIRONMENT":
        if out.name != "Color":
            raise _Unsupported(f"Environment Texture '{node.name}' output '{out.name}'")
        key = node.name
        if key not in textures:
            textures[key] = _environment_texture(node, warnings, world)
        return _Term(np.zeros(3), np.ones(3), textures[key])
    if node.type == "RGB":
        return _Term(np.array(out.default_value[:3], dtype=np.float64))
    if node.type in ("MIX_RGB", "MIX"):
        if node.type == "MIX":
            if node.data_type != "RGBA":
                raise _Unsupported(f"Mix node '{node.name}' of type {node.data_type}")
            fac_socket, a_socket, b_socket = (node.inputs["Factor_Float"], node.inputs["A_Color"],
                                              node.inputs["B_Color"])
            clamp = node.clamp_result
        else:
            fac_socket, a_socket, b_socket = node.inputs[0], node.inputs[1], node.inputs[2]
            clamp = node.use_clamp
        fac = min(max(_number(node, fac_socket, warnings, world), 0.0), 1.0)
        a = _colour_term(a_socket, warnings, world, textures)
        b = _colour_term(b_socket, warnings, world, textures)
        textured = a.texture is not None or b.texture is not None
        if clamp and textured:
            warnings.append(f"world '{world.name}': Mix '{node.name}' clamp ignored on the "
                            "environment texture")
        blend = node.blend_type
        if blend == "MIX":
            return a.scaled(1.0 - fac).plus(b.scaled(fac))
        if blend == "ADD":
            return a.plus(b.scaled(fac))
        if blend == "MULTIPLY":
            if a.texture is not None and b.texture is not None:
                raise _Unsupported(f"Mix '{node.name}' multiplies two textures")
            tex, const = (a, b) if b.texture is None else (b, a)
            factor = (1.0 - fac) + fac * const.color
            if tex is b:  # (1 − f)·A + f·A·B with A constant, B textured
                return _Term(a.color * (1.0 - fac), a.color * fac * b.weight, b.texture).plus(
                    _Term(a.color * fac * b.color))
            return _Term(tex.color * factor, tex.weight * factor, tex.texture)
        raise _Unsupported(f"Mix '{node.name}' blend {blend} (only Mix, Add, Multiply)")
    raise _Unsupported(f"node '{node.name}' ({node.type}) feeding a colour")


def _shader_term(socket, warnings, world, textures):
    out = _linked_from(socket)
    if out is None:
        return _Term(np.zeros(3))
    node = out.node
    if node.type == "BACKGROUND":
        strength = _number(node, node.inputs["Strength"], warnings, world)
        try:
            colour = _colour_term(node.inputs["Color"], warnings, world, textures)
        except _Unsupported as why:
            warnings.append(f"world '{world.name}': {why}; Background '{node.name}' uses its "
                            "Color socket's default value")
            colour = _Term(_constant(node.inputs["Color"]))
        return colour.scaled(strength)
    if node.type == "MIX_SHADER":
        fac = min(max(_number(node, node.inputs[0], warnings, world), 0.0), 1.0)
        a = _shader_term(node.inputs[1], warnings, world, textures)
        b = _shader_term(node.inputs[2], warnings, world, textures)
        return a.scaled(1.0 - fac).plus(b.scaled(fac))
    if node.type == "ADD_SHADER":
        return _shader_term(node.inputs[0], warnings, world, textures).plus(
            _shader_term(node.inputs[1], warnings, world, textures))
    raise _Unsupported(f"shader node '{node.name}' ({node.type})")


def _sampling(world):
    cycles = getattr(world, "cycles", None)
    method = getattr(cycles, "sampling_method", "AUTOMATIC")
    resolution = int(getattr(cycles, "sample_map_resolution", 1024))
    if method == "NONE":
        return "none", 0
    if method == "MANUAL":
        return "manual", resolution + resolution % 2
    return "auto", 0


def world_dict(world, warnings):
    """The world as the renderer takes it (see the module docstring); appends to `warnings`."""
    if world is None:
        return {"color": np.zeros(3, dtype=np.float32)}
    fallback = {"color": np.array(world.color[:3], dtype=np.float32)}
    if not world.use_nodes or world.node_tree is None:
        return fallback
    output = next((n for n in world.node_tree.nodes
                   if n.type == "OUTPUT_WORLD" and n.is_active_output), None)
    if output is None:
        return {"color": np.zeros(3, dtype=np.float32)}
    if output.inputs["Volume"].is_linked:
        warnings.append(f"world '{world.name}': the world volume is not rendered")
    textures = {}
    try:
        term = _shader_term(output.inputs["Surface"], warnings, world, textures)
    except (_Unsupported, KeyError) as why:
        warnings.append(f"world '{world.name}': {why}; the world was replaced by its viewport "
                        f"colour {tuple(round(c, 3) for c in world.color[:3])}")
        return fallback
    out = {"color": np.maximum(term.color, 0.0).astype(np.float32)}
    if term.texture is not None and np.any(term.weight > 0.0):
        tex = dict(term.texture)
        tex["matrix"] = np.asarray(tex["matrix"], dtype=np.float64)
        tex["weight"] = np.maximum(term.weight, 0.0).astype(np.float32)
        out["texture"] = tex
        out["sampling"], out["map_resolution"] = _sampling(world)
    return out
