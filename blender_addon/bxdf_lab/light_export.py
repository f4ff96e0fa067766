"""Blender lights → the renderer's lights (plugin/include/bxdf/render/lights.h), as Cycles 3.4
renders them.

Units follow Blender: a point or spot light of power P watts has radiant intensity
I = P·colour/(4π) W/sr and, with a radius r, is a disk facing the shaded point of radiance
I/(π r²); a sun gives irradiance `strength` W/m² spread over its angle; an area light of power P
emits radiance P·colour/(4·area) from its front (−Z) only. A light's node tree may scale it by a
constant Emission node (colour × strength, as Cycles multiplies them); its object's
visible_camera and the light's cast_shadow and Multiple Importance settings are passed on.
Whatever Cycles would do that the renderer does not is named in a warning.
"""

import math

import numpy as np

# Ray visibility flags the renderer has no equivalent for (Cycles hides the light from those
# bounces).
_UNSUPPORTED_VISIBILITY = ("visible_diffuse", "visible_glossy", "visible_transmission",
                           "visible_volume_scatter")


def _emission_factor(light, name, warnings):
    """Colour × Strength of a constant Emission node feeding the light's output, or 1."""
    if not light.use_nodes or light.node_tree is None:
        return np.ones(3, dtype=np.float32)
    output = next((n for n in light.node_tree.nodes
                   if n.type == "OUTPUT_LIGHT" and n.is_active_output), None)
    if output is None or not output.inputs["Surface"].is_linked:
        return np.ones(3, dtype=np.float32)
    node = output.inputs["Surface"].links[0].from_node
    if node.type != "EMISSION":
        warnings.append(f"light '{name}': its node tree ends in '{node.name}' ({node.type}), "
                        "not an Emission node; rendered with colour and strength 1")
        return np.ones(3, dtype=np.float32)
    colour, strength = node.inputs["Color"], node.inputs["Strength"]
    if colour.is_linked or strength.is_linked:
        warnings.append(f"light '{name}': Emission '{node.name}' has linked inputs (textured "
                        "lights are not rendered); their default values were used")
    return np.array(colour.default_value[:3], dtype=np.float32) * float(strength.default_value)


def light_dict(obj, matrix, warnings):
    """One light in Blender's units plus what the renderer derives from them."""
    light = obj.data
    name = obj.name
    m = np.array(matrix, dtype=np.float32).reshape(4, 4)
    color = np.array(light.color, dtype=np.float32) * _emission_factor(light, name, warnings)
    cycles = getattr(light, "cycles", None)
    out = {
        "type": light.type.lower(),  # point, spot, sun, area
        "name": name,
        "matrix": m,
        "position": m[:3, 3].copy(),
        "direction": -m[:3, 2] / max(np.linalg.norm(m[:3, 2]), 1e-30),  # lights shine along -Z
        "color": color,
        "power": float(light.energy),  # W (sun: W/m²)
        "visible_camera": bool(obj.visible_camera),
        "cast_shadow": bool(getattr(cycles, "cast_shadow", True)),
        "use_mis": bool(getattr(cycles, "use_multiple_importance_sampling", True)),
    }
    hidden = [flag[len("visible_"):] for flag in _UNSUPPORTED_VISIBILITY
              if not getattr(obj, flag, True)]
    if hidden:
        warnings.append(f"light '{name}': ray visibility off for {', '.join(hidden)} is ignored "
                        "(the light reaches every bounce)")
    if getattr(cycles, "is_portal", False):
        warnings.append(f"light '{name}': portals are not supported; the portal is ignored")
        out["power"] = 0.0
    if light.type in ("POINT", "SPOT"):
        out["radius"] = float(light.shadow_soft_size)
        out["intensity"] = color * float(light.energy) / (4.0 * math.pi)  # W/sr
    if light.type == "SPOT":
        out["spot_size"] = float(light.spot_size)  # full cone angle, radians
        out["spot_blend"] = float(light.spot_blend)
    if light.type == "SUN":
        out["angle"] = min(float(light.angle), math.pi * 0.999)
        out["irradiance"] = color * float(light.energy)  # W/m²
    if light.type == "AREA":
        size_x = float(light.size)
        size_y = float(light.size_y) if light.shape in ("RECTANGLE", "ELLIPSE") else size_x
        out.update(shape=light.shape.lower(), size=(size_x, size_y))
        if light.spread < math.pi - 1e-6:
            warnings.append(f"light '{name}': spread {math.degrees(light.spread):.1f}° rendered "
                            "as 180°")
    return out
