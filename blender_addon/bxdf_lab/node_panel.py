"""The material panel's source switch and, for a material rendered from its node tree, what the
translation made of it: coverage counts and its warnings."""

from . import material_source, nodes


def draw_source(layout, material):
    """Draws the switch; returns the material's source ("NODES" or "MODEL")."""
    source = material_source.source(material)
    row = layout.row(align=True)
    for identifier, label, _ in material_source.SOURCES:
        op = row.operator("bxdf_lab.set_material_source", text=label,
                          depress=identifier == source)
        op.source = identifier
    if source == "NODES":
        draw_translation(layout, material)
    return source


def draw_translation(layout, material):
    translation = nodes.translate(material, write_files=False)
    counts = {"exact": 0, "approximate": 0, "unsupported": 0}
    for entry in translation.coverage.values():
        counts[entry["status"]] += 1
    layout.label(text=f"{len(translation.graph.closures)} closure(s) from "
                      f"{len(translation.coverage)} node(s): {counts['exact']} exact, "
                      f"{counts['approximate']} approximate, {counts['unsupported']} unsupported",
                 icon="NODETREE")
    if translation.warnings:
        column = layout.column(align=True)
        column.alert = True
        prefix = f"material '{material.name}': "
        for warning in translation.warnings:
            column.label(text=warning.removeprefix(prefix), icon="ERROR")
