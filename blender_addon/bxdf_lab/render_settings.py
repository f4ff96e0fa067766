"""The BXDF_LAB engine's render settings: `scene.bxdf_lab_render` (Render tab)."""

import bpy
from bpy.props import EnumProperty, FloatProperty, IntProperty, PointerProperty


class BXDFLAB_PG_render_settings(bpy.types.PropertyGroup):
    samples: IntProperty(name="Samples", description="Samples per pixel", default=64, min=1,
                         soft_max=4096, max=1 << 20)
    preview_samples: IntProperty(name="Preview Samples",
                                 description="Samples per pixel of the Material tab's preview",
                                 default=32, min=1, soft_max=256, max=1 << 16)
    viewport_samples: IntProperty(name="Viewport Samples",
                                  description="Samples per pixel of the viewport's Rendered mode "
                                              "(refined pass by pass)",
                                  default=32, min=1, soft_max=1024, max=1 << 16)
    max_bounces: IntProperty(name="Max Bounces",
                             description="Longest path; 0 = direct light only", default=8, min=0,
                             max=1024, soft_max=64)
    pixel_filter: EnumProperty(
        name="Pixel Filter", default="BLACKMAN_HARRIS",
        items=[("BOX", "Box", "Uniform over the pixel"),
               ("GAUSSIAN", "Gaussian", "Gaussian of the given width, as Cycles' Gaussian"),
               ("BLACKMAN_HARRIS", "Blackman-Harris",
                "Blackman-Harris window of the given width (Cycles' default filter)"),
               ("PIXEL_CENTER", "Pixel Centre", "One ray through each pixel's centre "
                                                "(Cycles' nearest is Gaussian of width 0.01, "
                                                "which still spreads rays by 0.0025 px)")])
    filter_width: FloatProperty(name="Filter Width", description="Pixel filter width in pixels",
                                default=1.5, min=0.01, max=10.0, subtype="PIXEL")
    threads: IntProperty(name="Threads", description="Worker threads; 0 = all cores", default=0,
                         min=0, max=1024)
    seed: IntProperty(name="Seed", description="Random seed of the sampler", default=0, min=0)


def register():
    bpy.utils.register_class(BXDFLAB_PG_render_settings)
    bpy.types.Scene.bxdf_lab_render = PointerProperty(type=BXDFLAB_PG_render_settings,
                                                      name="BxDF Lab Render")


def unregister():
    del bpy.types.Scene.bxdf_lab_render
    bpy.utils.unregister_class(BXDFLAB_PG_render_settings)
