"""Cycles' closure budget, reproduced for the scene being rendered.

Cycles gives every shader evaluation the same number of closure slots: the largest
`ShaderGraph::get_num_closures()` over the scene's shaders (Principled 8, Glass and multiscatter
GGX 2, every other closure node 1; the world's Background and the default surface 1), at most
MAX_CLOSURE. Closures are allocated in the shader's evaluation order; one that needs a
MicrofacetExtra takes a second slot, and when that second slot is not free `closure_alloc_extra`
removes the closure again (kernel/closure/alloc.h). So a lone Principled BSDF with every lobe
(diffuse, sheen, specular, glass reflection and refraction, clearcoat: 9 slots) loses its
clearcoat. A second Transparent closure merges into the first and takes no slot; emission and
holdout take none.

The simulation uses each lobe's constant inputs; a lobe driven per hit is assumed present.
"""

MAX_CLOSURE = 64  # kernel/types.h (CPU)
# Principled lobes whose removal a registry parameter expresses exactly.
DROPPABLE_PARAMS = {"clearcoat": "clearcoat", "sheen": "sheen"}


def scene_budget(translations):
    """Slots per shader evaluation for a scene whose node materials are `translations` (at
    least 1: the world's Background and Cycles' default surface)."""
    counts = [sum(t.closure_counts.values()) for t in translations]
    return min(max([1] + counts), MAX_CLOSURE)


def allocate(translation, budget):
    """[(closure index, lobe, slots)] of the lobes Cycles drops for lack of slots."""
    left, transparent_seen, dropped = budget, False, []
    for index, record in enumerate(translation.lobes):
        for lobe, slots, active in record["lobes"]:
            if not active:
                continue
            if record["model"] == "cycles_transparent":
                if transparent_seen:
                    continue
                transparent_seen = True
            if left == 0 or slots > left:
                dropped.append((index, lobe, slots))
                continue
            left -= slots
    return dropped


def apply(translation, budget):
    """Removes what Cycles drops from the translation's graph, each with a warning naming the
    material and the dropped closure; what a parameter cannot express is only reported."""
    closures = translation.graph.closures
    removed = set()
    for index, lobe, slots in allocate(translation, budget):
        record = translation.lobes[index]
        closure = closures[index]
        where = f"material '{translation.material.name}': node '{record['node']}'"
        reason = (f"Cycles' closure budget for this scene is {budget} slots per shader and the "
                  f"{lobe} ({slots} slot{'s' if slots > 1 else ''}) does not fit")
        if lobe in DROPPABLE_PARAMS:
            closure["params"][DROPPABLE_PARAMS[lobe]] = 0.0
            translation.warnings.append(f"{where}: {reason}; dropped, as Cycles drops it")
        elif len(record["lobes"]) == 1:
            removed.add(index)
            translation.warnings.append(f"{where}: {reason}; the {closure['model']} closure "
                                        "is dropped, as Cycles drops it")
        else:
            translation.warnings.append(f"{where}: {reason}; Cycles drops it, BXDF_LAB keeps it "
                                        "(no parameter removes that lobe alone)")
    if removed:
        translation.graph.closures = [c for i, c in enumerate(closures) if i not in removed]
        translation.lobes = [r for i, r in enumerate(translation.lobes) if i not in removed]
    return translation

