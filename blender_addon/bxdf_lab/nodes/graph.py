"""The material graph being built (docs/material-graph.md): value nodes in evaluation order,
closures with folded weights, emission terms and textures.

A value is a constant (a float or a 3-tuple) or a reference {"node": i, "out": name} to an
earlier node's output. Constants are kept in Python where that is exact (Mix Shader weights with a
constant factor); anything that depends on a reference becomes a node.
"""

# Cycles' Rec.709 luminance, the colour → float socket conversion (docs/material-graph.md).
LUMINANCE = (0.2126729, 0.7151522, 0.0721750)


def is_reference(value):
    return isinstance(value, dict)


def is_constant(value):
    return not is_reference(value)


def to_float(value):
    """A constant as a float (colours by Cycles' luminance)."""
    if isinstance(value, (tuple, list)):
        return sum(w * float(c) for w, c in zip(LUMINANCE, value))
    return float(value)


def to_triple(value):
    """A constant as a 3-tuple (a float is grey)."""
    if isinstance(value, (tuple, list)):
        return tuple(float(c) for c in value[:3])
    return (float(value),) * 3


def convert(value, kind):
    """A constant converted to the socket kind `kind` ("float" or "triple"); references are left
    for the renderer, which converts them as Cycles converts sockets."""
    if is_reference(value):
        return value
    return to_float(value) if kind == "float" else to_triple(value)


class Graph:
    """Accumulates the program; `as_dict()` gives the "graph" of docs/material-graph.md."""

    def __init__(self):
        self.nodes = []
        self.closures = []
        self.emission_terms = []
        self.textures = []
        self._texture_index = {}
        self._emission = None

    def add(self, op, outputs, **fields):
        """Appends a node; returns {output name: reference}."""
        index = len(self.nodes)
        self.nodes.append({"op": op, **fields})
        return {name: {"node": index, "out": name} for name in outputs}

    def texture(self, record):
        """The index of a texture record, shared by every node reading the same image and mode."""
        key = tuple(sorted((k, str(v)) for k, v in record.items()))
        if key not in self._texture_index:
            self._texture_index[key] = len(self.textures)
            self.textures.append(dict(record))
        return self._texture_index[key]

    # ---- weights: products of Mix/Add Shader factors -------------------------------------

    def multiply(self, a, b):
        """a·b for float weights; constants stay constants."""
        if is_constant(a) and is_constant(b):
            return to_float(a) * to_float(b)
        if is_constant(a) and to_float(a) == 1.0:
            return b
        if is_constant(b) and to_float(b) == 1.0:
            return a
        return self.add("math", ["value"], operation="multiply", clamp=False, a=a, b=b,
                        c=0.0)["value"]

    def saturate(self, value):
        """Clamped to [0, 1], as Cycles clamps a Mix Shader's factor."""
        if is_constant(value):
            return min(max(to_float(value), 0.0), 1.0)
        return self.add("math", ["value"], operation="multiply", clamp=True, a=value, b=1.0,
                        c=0.0)["value"]

    def one_minus(self, value):
        if is_constant(value):
            return 1.0 - to_float(value)
        return self.add("math", ["value"], operation="subtract", clamp=False, a=1.0, b=value,
                        c=0.0)["value"]

    def scale_colour(self, colour, factor):
        """colour·factor (RGB × float), for emission terms."""
        if is_constant(colour) and is_constant(factor):
            return tuple(c * to_float(factor) for c in to_triple(colour))
        return self.add("vector_math", ["vector", "value"], operation="scale", a=colour,
                        b=(0.0, 0.0, 0.0), c=(0.0, 0.0, 0.0), scale=factor)["vector"]

    def emission(self):
        """The sum of the emission terms (constant where they all are); built once, after the
        last term."""
        if self._emission is None:
            self._emission = self._sum_emission()
        return self._emission

    def _sum_emission(self):
        total = (0.0, 0.0, 0.0)
        references = []
        for term in self.emission_terms:
            if is_constant(term):
                total = tuple(t + c for t, c in zip(total, to_triple(term)))
            else:
                references.append(term)
        result = total
        for term in references:
            if is_constant(result) and result == (0.0, 0.0, 0.0):
                result = term
            else:
                result = self.add("vector_math", ["vector", "value"], operation="add", a=result,
                                  b=term, c=(0.0, 0.0, 0.0), scale=1.0)["vector"]
        return list(result) if is_constant(result) else result

    def as_dict(self):
        emission = self.emission()
        return {"nodes": self.nodes, "closures": self.closures, "emission": emission,
                "textures": self.textures}
