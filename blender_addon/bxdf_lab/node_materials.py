"""Export of materials that render from their node trees (material_source.py): their material
graphs (nodes/), Cycles' closure budget for the scene, and the mesh data the graphs read.

Per material: {"name", "graph"} (docs/material-graph.md).

Per mesh, for the UV maps its materials' graphs read: "uv_maps", a list aligned with the scene's
"uv_map_names" ("" = the mesh's active render map) of per-corner UVs ((T·3, 2) float32; zeros
where the mesh has no such map, as Cycles reads (0, 0)); "tangents", aligned the same way, None or,
for a map a Normal Map reads, per-corner (T·3, 4) float32: the object-space tangent and the
bitangent sign from `mesh.calc_tangents`; both lists are empty when no graph reads a UV map, and
a map no graph reads is zeros. "texture_space" ((2, 3) float32: location, size): Cycles'
generated coordinates are (P_object − location) / (2·size) + 0.5.

The scene's "closure_budget" is Cycles' closure slots per shader, None when no material renders
from nodes (nothing to budget).
"""

import numpy as np

from . import nodes
from .nodes import closure_budget, registry_params


def _tangent_maps(translation):
    """The graph's indices of the UV maps whose tangents its Normal Map nodes read."""
    return {n.get("map", 0) for n in translation.graph.nodes if n["op"] == "normal_map"}


def _maps_read(translation):
    """The graph's indices of the UV maps its nodes read (UV coordinates, normal-map tangents)."""
    return {n.get("map", 0) for n in translation.graph.nodes if n["op"] in ("uv", "normal_map")}


class NodeMaterials:
    def __init__(self):
        self.translations = []   # (entry dict, Translation) of the materials rendered from nodes
        # Model materials with node trees: only Cycles' closure budget needs them, and only when
        # some material renders from nodes; finish() translates them then.
        self.cycles_only = []

    def entry(self, material):
        """The scene material of a node-tree material (its graph is filled in by finish())."""
        translation = nodes.translate(material)
        entry = {"name": material.name}
        self.translations.append((entry, translation))
        return entry

    def count_for_cycles(self, material):
        """A material rendered from its BxDF Lab model still has a node tree that Cycles renders
        (a comparison's set-up): it sizes Cycles' closure budget like any other."""
        if material.use_nodes and material.node_tree is not None:
            self.cycles_only.append(material)

    def _translation(self, material):
        return next((t for _, t in self.translations if t.material == material), None)

    def needs_tangents(self, materials):
        """Whether the graph of any of `materials` has a Normal Map node, whose tangents
        mesh_attributes computes on the mesh (calc_tangents)."""
        for material in materials:
            translation = self._translation(material) if material is not None else None
            if translation is not None and _tangent_maps(translation):
                return True
        return False

    def mesh_attributes(self, mesh, data, materials):
        """UV maps, tangents and texture space that the graphs of `materials` read on `mesh`
        (keys of the module docstring, with "uv_layers" keyed by graph UV map name until
        finish() aligns them); warnings go to the translations."""
        out = {"texture_space": np.array([mesh.texspace_location, mesh.texspace_size],
                                         dtype=np.float32), "uv_layers": {}}
        corners = data["uv_indices"]
        for material in materials:
            translation = self._translation(material) if material is not None else None
            if translation is None or corners is None:
                continue
            tangent_maps = _tangent_maps(translation)
            read = _maps_read(translation)
            for index, name in enumerate(translation.uv_maps):
                if index not in read:
                    continue  # not read by the graph (the active render map "" always has an index)
                if name in out["uv_layers"] and (index not in tangent_maps or
                                                 "tangents" in (out["uv_layers"][name] or {})):
                    continue
                out["uv_layers"][name] = self._uv_layer(mesh, name, corners, index in tangent_maps,
                                                        translation)
        return out

    @staticmethod
    def _uv_layer(mesh, name, corners, with_tangents, translation):
        layer = (next((l for l in mesh.uv_layers if l.active_render), None) if name == ""
                 else mesh.uv_layers.get(name))
        if layer is None:
            if name:
                translation.warn(None, (), f"mesh '{mesh.name}' has no UV map '{name}'; its "
                                 "coordinates read as (0, 0), as in Cycles")
            return None
        n_loops = len(mesh.loops)
        uvs = np.empty(n_loops * 2, dtype=np.float32)
        layer.data.foreach_get("uv", uvs)
        layer_name = layer.name  # the layer's Python object does not survive calc_tangents
        out = {"name": layer_name, "uvs": uvs.reshape(n_loops, 2)[corners.ravel()]}
        if with_tangents:
            try:
                mesh.calc_tangents(uvmap=layer_name)
            except RuntimeError as exc:  # n-gons: Blender computes tangents of tris and quads only
                reason = str(exc).strip().removeprefix("Error: ")
                translation.warn(None, (), f"mesh '{mesh.name}': no tangents for UV map "
                                 f"'{layer_name}' ({reason}); Normal Map nodes on it have none to read")
                return out
            tangents = np.empty((n_loops, 4), dtype=np.float32)
            xyz = np.empty(n_loops * 3, dtype=np.float32)
            mesh.loops.foreach_get("tangent", xyz)
            tangents[:, :3] = xyz.reshape(n_loops, 3)
            signs = np.empty(n_loops, dtype=np.float32)
            mesh.loops.foreach_get("bitangent_sign", signs)
            tangents[:, 3] = signs
            mesh.free_tangents()
            out["tangents"] = tangents[corners.ravel()]
        return out

    def finish(self, scene_data):
        """Applies Cycles' closure budget, fills each entry's graph, aligns the meshes' UV maps
        with the scene's "uv_map_names" and adds the translations' warnings."""
        translations = [t for _, t in self.translations]
        # Without node materials no graph has closures to budget (None says so).
        budget = (closure_budget.scene_budget(
            translations + [nodes.translate(m) for m in self.cycles_only]) if translations else None)
        names = [""] + sorted({n for t in translations for n in t.uv_maps} - {""})
        for entry, translation in self.translations:
            closure_budget.apply(translation, budget)
            graph = translation.graph.as_dict()
            scene_index = [names.index(n) for n in translation.uv_maps]
            for node in graph["nodes"]:
                if node["op"] in ("uv", "normal_map"):
                    node["map"] = scene_index[node["map"]]
            entry["graph"] = graph
            for closure in graph["closures"]:
                model = closure["model"]
                if model != "holdout" and model not in registry_params.models():
                    translation.warn(None, (), f"model '{model}' is not in this build of bxdf "
                                     "(bxdf.models()); the renderer cannot render it")
            scene_data["warnings"].extend(translation.warnings)
        # Per-corner UV maps only when a graph reads one: without, a mesh carries none (zeros
        # per corner for every mesh would be copied and stored for nothing).
        any_read = any(_maps_read(t) for t in translations)
        for mesh in scene_data["meshes"]:
            layers = mesh.pop("uv_layers", {})
            corners = 3 * len(mesh["triangles"])
            mesh["uv_maps"] = [layers[n]["uvs"] if layers.get(n) else
                               np.zeros((corners, 2), dtype=np.float32) for n in names] if any_read else []
            mesh["tangents"] = [(layers.get(n) or {}).get("tangents") for n in names] if any_read else []
        scene_data["uv_map_names"] = names
        scene_data["closure_budget"] = budget

