"""Closure parameters derived from the model registry (`bxdf.models()`), never listed here.

A BSDF node's input socket feeds the registry parameter of the same name in snake case
("Base Color" → `base_color`, "IOR" → `ior`). A constant outside the registry's range is clamped
into it with a warning; an enum value the registry does not know is a warning and takes the
registry's default.
"""

import math

from .. import dependency, schema
from . import graph as g

_models = {}


def models():
    """{model name: schema.Model} of the loaded `bxdf` module (read once)."""
    if not _models:
        _models.update(schema.read_models(dependency.require()))
    return _models


def param_name(socket_name):
    return socket_name.strip().lower().replace(" ", "_")


def from_sockets(scope, model, exclude=()):
    """{registry parameter: value} for every input socket of the node whose snake-case name is a
    float or RGB parameter of `model` (every such socket when the registry lacks the model: the
    export then reports the missing model)."""
    known = models().get(model)
    wanted = ({p.name: p.kind for p in known.params if p.kind in ("float", "rgb")}
              if known else None)
    params = {}
    for socket in scope.node.inputs:
        if not socket.enabled or socket.name in exclude or socket.type == "SHADER":
            continue
        name = param_name(socket.name)
        if wanted is None or name in wanted:
            kind = "float" if (wanted or {}).get(name, "") == "float" else None
            params[name] = scope.input(socket.identifier, kind)
    return params


def _clamp(param, value):
    lo = param.min if math.isfinite(param.min) else -3.4e38
    hi = param.max if math.isfinite(param.max) else 3.4e38
    if param.min_exclusive:
        lo = math.nextafter(lo, math.inf) if lo == 0.0 else lo + 1e-6 * max(abs(lo), 1.0)
    if param.max_exclusive:
        hi = hi - 1e-6 * max(abs(hi), 1.0)
    return min(max(value, lo), hi)


def checked(scope, model, params):
    """`params` with constants converted to each parameter's kind and clamped into range."""
    known = models().get(model)
    if known is None:
        return dict(params)
    out = {}
    for name, value in params.items():
        try:
            param = known.param(name)
        except KeyError:
            scope.warn(f"model '{model}' has no parameter '{name}'; the value is left out")
            continue
        if param.kind == "enum":
            if str(value) not in param.choices:
                scope.warn(f"'{value}' is not a {model} {name} this build knows "
                           f"({', '.join(param.choices)}); {param.default} is used instead")
                value = str(param.default)
            out[name] = str(value)
        elif param.kind in ("float", "rgb") and g.is_constant(value):
            given = g.to_float(value) if param.kind == "float" else list(g.to_triple(value))
            clamped = (_clamp(param, given) if param.kind == "float"
                       else [_clamp(param, c) for c in given])
            if clamped != given:
                scope.warn(f"{model} {name} = {given} is outside {param.range_text()}; "
                           f"{clamped} is used instead")
            out[name] = clamped
        else:
            out[name] = value
    return out
