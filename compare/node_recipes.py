"""Materials built only from Blender shader nodes, for the node scenes (runs inside Blender).

Each recipe fills a material's node tree as a Blender user would, with no BxDF Lab set-up at
all: BXDF_LAB renders the tree through the add-on's node translation, Cycles renders it itself.
Textures are generated here (numpy → generated Blender images; no files are downloaded).
"""
from __future__ import annotations

import bpy
import numpy as np


def _tree(material):
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    return material.node_tree, output


def _principled(material, **inputs):
    tree, output = _tree(material)
    node = tree.nodes.new("ShaderNodeBsdfPrincipled")
    for name, value in inputs.items():
        node.inputs[name.replace("_", " ")].default_value = value
    tree.links.new(node.outputs[0], output.inputs["Surface"])
    return node


def gold(material):
    _principled(material, Base_Color=(1.0, 0.766, 0.336, 1.0), Metallic=1.0, Roughness=0.25)


def plastic_clearcoat(material):
    _principled(material, Base_Color=(0.6, 0.05, 0.04, 1.0), Roughness=0.45, Clearcoat=1.0,
                Clearcoat_Roughness=0.05)


def sheen_fabric(material):
    _principled(material, Base_Color=(0.1, 0.15, 0.5, 1.0), Roughness=0.9, Specular=0.2,
                Sheen=1.0, Sheen_Tint=0.3)


def brushed_metal(material):
    _principled(material, Base_Color=(0.9, 0.9, 0.92, 1.0), Metallic=1.0, Roughness=0.35,
                Anisotropic=0.8)


def glass(material):
    _principled(material, Base_Color=(1.0, 1.0, 1.0, 1.0), Roughness=0.0, Transmission=1.0,
                IOR=1.5)


def mix_diffuse_glossy(material):
    tree, output = _tree(material)
    mix = tree.nodes.new("ShaderNodeMixShader")
    mix.inputs["Fac"].default_value = 0.35
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.2, 0.5, 0.2, 1.0)
    glossy = tree.nodes.new("ShaderNodeBsdfGlossy")
    glossy.inputs["Roughness"].default_value = 0.2
    tree.links.new(diffuse.outputs[0], mix.inputs[1])
    tree.links.new(glossy.outputs[0], mix.inputs[2])
    tree.links.new(mix.outputs[0], output.inputs["Surface"])


TEXTURE_SIZE = 256
TILES = 8


def _generated_image(name, pixels, colorspace):
    """A generated float image holding `pixels` ((h, w, 3), rows bottom-up as Blender's)."""
    height, width, _ = pixels.shape
    image = bpy.data.images.new(name, width, height, float_buffer=True)
    image.colorspace_settings.name = colorspace  # first: a change regenerates the pixels
    rgba = np.concatenate([pixels, np.ones((height, width, 1))], axis=2).astype(np.float32)
    image.pixels.foreach_set(rgba.ravel())
    return image


def checker_pixels(size=TEXTURE_SIZE, tiles=TILES):
    """A two-colour checker with a soft gradient across it (linear values)."""
    v, u = (np.mgrid[0:size, 0:size] + 0.5) / size
    cells = (np.floor(u * tiles) + np.floor(v * tiles)) % 2
    light, dark = np.array([0.75, 0.7, 0.6]), np.array([0.12, 0.1, 0.08])
    pixels = np.where(cells[..., None] > 0, light, dark)
    return pixels * (0.7 + 0.3 * u)[..., None]


def tile_normal_pixels(size=TEXTURE_SIZE, tiles=TILES, bevel=0.15):
    """A tangent-space normal map of bevelled tiles: the normal tilts outwards near each tile's
    edges ((n + 1)/2 encoding, Non-Color)."""
    v, u = (np.mgrid[0:size, 0:size] + 0.5) / size
    fu, fv = (u * tiles) % 1.0, (v * tiles) % 1.0
    slope = lambda f: np.where(f < bevel, -(1 - f / bevel), np.where(f > 1 - bevel,
                                                                     (f - 1 + bevel) / bevel, 0.0))
    n = np.stack([slope(fu) * 0.6, slope(fv) * 0.6, np.ones_like(u)], axis=-1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    return n * 0.5 + 0.5


def textured_floor(material):
    """A Mix of a Diffuse BSDF whose colour is an image and a Glossy BSDF whose normal comes from
    a tangent-space normal map (another image)."""
    tree, output = _tree(material)
    links = tree.links
    mix = tree.nodes.new("ShaderNodeMixShader")
    mix.inputs["Fac"].default_value = 0.3
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    glossy = tree.nodes.new("ShaderNodeBsdfGlossy")
    glossy.inputs["Roughness"].default_value = 0.3
    colour = tree.nodes.new("ShaderNodeTexImage")
    colour.image = _generated_image("floor_colour", checker_pixels(), "Linear")
    normals = tree.nodes.new("ShaderNodeTexImage")
    normals.image = _generated_image("floor_normals", tile_normal_pixels(), "Non-Color")
    normal_map = tree.nodes.new("ShaderNodeNormalMap")
    links.new(colour.outputs["Color"], diffuse.inputs["Color"])
    links.new(normals.outputs["Color"], normal_map.inputs["Color"])
    links.new(normal_map.outputs[0], glossy.inputs["Normal"])
    links.new(diffuse.outputs[0], mix.inputs[1])
    links.new(glossy.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], output.inputs["Surface"])


RECIPES = {f.__name__: f for f in (gold, plastic_clearcoat, sheen_fabric, brushed_metal, glass,
                                   mix_diffuse_glossy, textured_floor)}


def build(material, recipe):
    try:
        RECIPES[recipe](material)
    except KeyError:
        raise ValueError(f"unknown node recipe {recipe!r}; known: {', '.join(RECIPES)}") from None
