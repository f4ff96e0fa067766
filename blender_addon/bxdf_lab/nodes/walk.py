"""Walking a Blender shader node tree from the active Material Output's Surface socket.

Links are followed through reroutes, muted nodes (their internal links, as Blender and Cycles do),
node groups (flattened: a group node's output continues at its Group Output, a Group Input at the
group node's input) and checked for validity; every other node is handed to its translator (one
module per node kind, `TRANSLATORS`). Results are cached per (group path, node, output), so a
node used twice becomes one graph node. A cycle or a broken link is a warning, never a crash.
"""

from . import graph as g
from . import registry_params

# Filled by nodes/__init__.py: {bl_idname: translator module}.
TRANSLATORS = {}

FLOAT_SOCKETS = {"VALUE", "INT", "BOOLEAN"}


def socket_kind(socket):
    return "float" if socket.type in FLOAT_SOCKETS else "triple"


def socket_default(socket):
    """The socket's own value, in its kind (colours without alpha); 0 for sockets with none."""
    value = getattr(socket, "default_value", None)
    if value is None:
        return 0.0 if socket_kind(socket) == "float" else (0.0, 0.0, 0.0)
    if isinstance(value, (int, float, bool)):
        return float(value)
    return g.to_triple(tuple(value))


def default_text(socket):
    """What an input falls back to, in a warning: its value, or for the hidden-value vector
    inputs Cycles fills itself, what Cycles uses."""
    if socket.type == "VECTOR" and getattr(socket, "hide_value", False):
        if socket.name == "Vector":
            return "its default texture coordinates"
        return "the smooth shading normal"
    return f"its default value {describe_value(socket_default(socket))}"


def describe_value(value):
    if isinstance(value, tuple):
        return "(" + ", ".join(f"{c:g}" for c in value) + ")"
    return f"{value:g}"


class Translation:
    """The translation of one material: its graph, warnings and per-node coverage."""

    def __init__(self, material, write_files=True):
        self.material = material
        self.write_files = write_files  # packed and generated images written to cache files
        self.graph = g.Graph()
        self.warnings = []
        self.coverage = {}      # node key → {"node", "type", "status", "why"}
        self.lobes = []         # per closure: Cycles' closure allocation (closure_budget.py)
        self.closure_counts = {}  # node → slots Cycles reserves for it (closure_budget.py)
        self.uv_maps = [""]     # UV map names the graph reads; "" = the active render map
        self.cache = {}         # (group path, node, output) → value
        self._visiting = set()

    # ---- reporting ----------------------------------------------------------------------

    def warn(self, node, path, text):
        where = f"node '{qualified_name(node, path)}' ({node.bl_idname}): " if node else ""
        warning = f"material '{self.material.name}': {where}{text}"
        if warning not in self.warnings:
            self.warnings.append(warning)

    def note(self, node, path, status, why):
        """Records a node's coverage; the worst status wins (unsupported > approximate > exact)."""
        key = qualified_name(node, path)
        rank = {"exact": 0, "approximate": 1, "unsupported": 2}
        entry = self.coverage.get(key)
        if entry is None:
            self.coverage[key] = {"node": key, "type": node.bl_idname, "status": status, "why": why}
        elif rank[status] > rank[entry["status"]]:
            entry.update(status=status, why=why)
        elif status == entry["status"] and why and why not in entry["why"]:
            entry["why"] = f"{entry['why']}; {why}" if entry["why"] else why

    def uv_map(self, name):
        """The graph's index of UV map `name` ("" = the active render map)."""
        if name not in self.uv_maps:
            self.uv_maps.append(name)
        return self.uv_maps.index(name)

    # ---- following links ----------------------------------------------------------------

    def resolve(self, socket, path, consumer):
        """Where an input socket's value comes from: ("default", socket, path) for a value of
        its own (unlinked, or a broken link, after a warning), or ("output", node, socket, path)."""
        seen = 0
        while True:
            seen += 1
            if seen > 10000:  # reroute or group loops that Blender did not flag
                self.warn(consumer, path, f"input '{socket.name}' is linked in a loop; "
                          f"{default_text(socket)} is used")
                return ("default", socket, path)
            links = [link for link in socket.links if not link.is_muted] if socket.is_linked else []
            if not links:
                return ("default", socket, path)
            link = links[0]
            if not link.is_valid:
                self.warn(consumer, path, f"input '{socket.name}' has an invalid link (a cycle or "
                          f"mismatched sockets); {default_text(socket)} is used")
                return ("default", socket, path)
            node, out = link.from_node, link.from_socket
            if node.bl_idname == "NodeReroute":
                socket = node.inputs[0]
                continue
            if node.mute:
                internal = next((l for l in node.internal_links if l.to_socket == out), None)
                if internal is None:
                    return ("default", out, path)  # a muted node without a pass-through
                socket = internal.from_socket
                continue
            if node.bl_idname == "NodeGroupInput":
                if not path:
                    return ("default", out, path)
                group_node = path[-1]
                socket = next((s for s in group_node.inputs if s.identifier == out.identifier), None)
                path = path[:-1]
                if socket is None:
                    return ("default", out, path)
                continue
            if node.bl_idname == "ShaderNodeGroup" or node.type == "GROUP":
                tree = node.node_tree
                output = group_output(tree)
                inner = (next((s for s in output.inputs if s.identifier == out.identifier), None)
                         if output else None)
                if inner is None:
                    self.note(node, path, "unsupported", "empty node group")
                    self.warn(node, path, f"the node group has no output '{out.name}'; input "
                              f"'{socket.name}' uses {default_text(socket)}")
                    return ("default", socket, path)
                self.note(node, path, "exact", "flattened")
                path = path + (node,)
                socket = inner
                continue
            return ("output", node, out, path)

    # ---- values ---------------------------------------------------------------------------

    def value(self, socket, path, consumer, kind=None):
        """The value feeding input `socket` of node `consumer`, as a constant of the socket's
        kind or a reference."""
        kind = kind or socket_kind(socket)
        found = self.resolve(socket, path, consumer)
        if found[0] == "default":
            return g.convert(socket_default(found[1]), kind)
        _, node, out, node_path = found
        if out.type == "SHADER":
            self.warn(consumer, path, f"input '{socket.name}' is fed by a shader output; "
                      f"{default_text(socket)} is used")
            return g.convert(socket_default(socket), kind)
        key = (tuple(n.name for n in node_path), node.name, out.identifier)
        if key in self.cache:
            return g.convert(self.cache[key], kind)
        if key in self._visiting:
            self.warn(consumer, path, f"input '{socket.name}' depends on itself (a cyclic node "
                      f"tree); {default_text(socket)} is used")
            return g.convert(socket_default(socket), kind)
        translator = TRANSLATORS.get(node.bl_idname)
        if translator is None or not hasattr(translator, "value"):
            self.note(node, node_path, "unsupported", "no translator for this node")
            self.warn(node, node_path, f"this node is not supported; input '{socket.name}' of node "
                      f"'{qualified_name(consumer, path)}' uses {default_text(socket)}")
            return g.convert(socket_default(socket), kind)
        self._visiting.add(key)
        try:
            result = translator.value(Scope(self, node_path, node), node, out)
        finally:
            self._visiting.discard(key)
        self.note(node, node_path, "exact", "")
        self.cache[key] = result
        return g.convert(result, kind)

    def closures(self, socket, path, consumer, weight):
        """Adds the closures feeding shader input `socket`, each weighted by `weight`."""
        found = self.resolve(socket, path, consumer)
        if found[0] == "default":
            return
        _, node, out, node_path = found
        if out.type != "SHADER":
            self._value_as_emission(socket, path, consumer, out, weight)
            return
        key = (tuple(n.name for n in node_path), node.name, "closure")
        if key in self._visiting:
            self.warn(consumer, path, f"shader input '{socket.name}' depends on itself (a cyclic "
                      "node tree); it contributes nothing")
            return
        translator = TRANSLATORS.get(node.bl_idname)
        if translator is None or not hasattr(translator, "closures"):
            self.note(node, node_path, "unsupported", "no translator for this shader")
            self.warn(node, node_path, "this shader node is not supported; it contributes nothing "
                      f"to input '{socket.name}' of node '{qualified_name(consumer, path)}'")
            return
        if g.is_constant(weight) and g.to_float(weight) == 0.0:
            return  # Cycles skips a closure whose mix weight is 0
        self._visiting.add(key)
        try:
            translator.closures(Scope(self, node_path, node), node, weight)
        finally:
            self._visiting.discard(key)
        self.note(node, node_path, "exact", "")


    def _value_as_emission(self, socket, path, consumer, out, weight):
        """A value linked into a shader input: Cycles inserts an Emission node, the value as its
        Strength (a float) or Color (anything else), the other input 1 (ShaderGraph::connect)."""
        graph = self.graph
        if out.type in FLOAT_SOCKETS:
            radiance = graph.scale_colour((1.0, 1.0, 1.0), self.value(socket, path, consumer, "float"))
        else:
            radiance = self.value(socket, path, consumer, "triple")
        graph.emission_terms.append(graph.scale_colour(radiance, weight))
        self.closure_counts[f"{qualified_name(consumer, path)}:{socket.identifier}#emission"] = 1


def qualified_name(node, path):
    return "/".join([n.name for n in path] + [node.name])


def group_output(tree):
    if tree is None:
        return None
    outputs = [n for n in tree.nodes if n.bl_idname == "NodeGroupOutput"]
    return next((n for n in outputs if n.is_active_output), outputs[0] if outputs else None)


class Scope:
    """What a translator sees: one node, in one group path, of one translation."""

    def __init__(self, translation, path, node):
        self.translation = translation
        self.path = path
        self.node = node
        self.graph = translation.graph

    def input(self, name, kind=None):
        """The value feeding the node's input `name` (a socket name or identifier)."""
        return self.translation.value(self.socket(name), self.path, self.node, kind)

    def socket(self, name):
        """The input with identifier `name`, else the enabled (then any) input named `name`."""
        inputs = self.node.inputs
        return (next((s for s in inputs if s.identifier == name), None) or
                next((s for s in inputs if s.name == name and s.enabled), None) or inputs[name])

    def linked(self, name):
        return self.translation.resolve(self.socket(name), self.path, self.node)[0] == "output"

    def closures(self, name, weight):
        self.translation.closures(self.socket(name), self.path, self.node, weight)

    def normal(self, name="Normal"):
        """A linked Normal input as a reference; None (the smooth normal) when unlinked."""
        if not self.linked(name):
            return None
        value = self.input(name, "triple")
        return value if g.is_reference(value) else None

    def with_normal(self, fields, name="Normal"):
        """`fields` plus "normal" when the node's Normal input is linked (ops whose normal is
        optional: unlinked, the renderer uses the smooth normal)."""
        normal = self.normal(name)
        if normal is not None:
            fields["normal"] = normal
        return fields

    def warn(self, text, status="approximate"):
        self.translation.note(self.node, self.path, status, text)
        self.translation.warn(self.node, self.path, text)

    def uv_map(self, name):
        return self.translation.uv_map(name)

    def add_closure(self, model, weight, params, normal=None, lobes=None, count=1, **extra):
        """Adds closure `model` with registry parameters `params` (constants checked against the
        registry's range). `lobes`: Cycles' slot allocation of this closure, [(lobe, slots,
        possibly active)] in allocation order; `count`: the slots Cycles' ShaderGraph reserves for
        the node (closure_budget.py)."""
        if g.is_constant(weight) and g.to_float(weight) == 0.0:
            return
        params = registry_params.checked(self, model, params)
        closure = {"model": model, "weight": weight, "params": params}
        if normal is not None:
            closure["normal"] = normal
        closure.update({k: v for k, v in extra.items() if v is not None})
        self.graph.closures.append(closure)
        key = qualified_name(self.node, self.path)
        self.translation.lobes.append({"node": key, "model": model, "weight": weight,
                                       "lobes": [("closure", 1, True)] if lobes is None else lobes})
        self.translation.closure_counts[f"{key}#{model}"] = count

    def emit(self, radiance, count=1):
        self.graph.emission_terms.append(radiance)
        self.translation.closure_counts[qualified_name(self.node, self.path) + "#emission"] = count

    def memo(self, what, make):
        """make() once per node and `what` (a node whose outputs share one graph node)."""
        key = (tuple(n.name for n in self.path), self.node.name, "#" + what)
        cache = self.translation.cache
        if key not in cache:
            cache[key] = make()
        return cache[key]
