"""Reads the model registry (`bxdf.models()`) into plain Python records.

The registry in the core is the single source of truth for every model's parameters; the
property groups, the panel, `api.assign` and the JSON operators all go through the records here.
Nothing in the add-on names a model's parameters itself.
"""

import math
from dataclasses import dataclass, field

KINDS = ("float", "rgb", "enum", "bool", "string", "list")
# Units as Blender shows them next to a value.
UNIT_SYMBOLS = {"degrees": "°"}
# Words of enum identifiers that Blender spells out (Cycles' "Multiscatter GGX").
_WORD_LABELS = {"multi": "Multiscatter"}


def enum_label(identifier):
    """Blender's name for an enum identifier: "ggx" → "GGX", "v_groove" → "V-Groove",
    "ashikhmin_shirley" → "Ashikhmin-Shirley", "multi_ggx" → "Multiscatter GGX". A word without
    a vowel is an acronym; words joined by "_" form one name (hyphenated), except after a
    spelled-out prefix."""
    words = identifier.split("_")
    shown = [w.upper() if not set(w) & set("aeiouy") else _WORD_LABELS.get(w, w.capitalize())
             for w in words]
    return (" " if words[0] in _WORD_LABELS else "-").join(shown)


@dataclass
class Param:
    name: str
    kind: str
    default: object
    min: float = -math.inf
    max: float = math.inf
    min_exclusive: bool = False
    max_exclusive: bool = False
    unit: str = ""
    doc: str = ""
    choices: list = field(default_factory=list)
    subtype: str = "color"                      # rgb kind: "color" or "per_channel"
    fields: list = field(default_factory=list)  # list kind: the schema of each element
    when_param: str = ""                        # shown only when when_param is in when_values
    when_values: list = field(default_factory=list)

    def range_text(self):
        if self.kind == "enum":
            return "{" + ", ".join(self.choices) + "}"
        if self.kind not in ("float", "rgb"):
            return ""
        lo = "(" if self.min_exclusive or math.isinf(self.min) else "["
        hi = ")" if self.max_exclusive or math.isinf(self.max) else "]"
        text = f"{lo}{_num(self.min)}, {_num(self.max)}{hi}"
        return f"{text} {self.unit}" if self.unit else text

    def tooltip(self):
        parts = [self.doc.rstrip(".")] if self.doc else []
        if self.range_text():
            parts.append(self.range_text())
        if self.when_param:
            parts.append(f"Used when {self.when_param} is {' or '.join(self.when_values)}")
        return ". ".join(parts)

    @property
    def is_color(self):
        """An RGB colour (drawn as a swatch), not three per-channel numbers (number fields)."""
        return self.kind == "rgb" and self.subtype == "color"

    @property
    def label(self):
        """Short enough for the default Properties width: title case, the unit as a symbol."""
        label = self.name.replace("_", " ").title()
        unit = UNIT_SYMBOLS.get(self.unit, self.unit)
        return f"{label} ({unit})" if unit else label

    def relevant(self, values):
        """Whether this parameter matters given the current values (a name → value mapping)."""
        if not self.when_param:
            return True
        return str(values.get(self.when_param)) in self.when_values


@dataclass
class Model:
    name: str
    params: list
    doc: str = ""

    @property
    def label(self):
        return self.name.replace("_", " ").title()

    def param(self, name):
        for p in self.params:
            if p.name == name:
                return p
        raise KeyError(name)


def _num(x):
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return f"{x:g}"


def _float(x, fallback):
    if x is None:
        return fallback
    return float(x)


def _when(spec):
    """The registry's condition {"param": p, "values": [...]} as (p, values); ("", []) if none."""
    when = spec.get("when")
    if not when:
        return "", []
    return str(when["param"]), [str(v) for v in when["values"]]


def param_from_spec(spec):
    kind = str(spec["kind"]).lower()
    if kind not in KINDS:
        raise ValueError(f"parameter '{spec.get('name')}': unknown kind '{kind}' in bxdf.models()")
    when_param, when_values = _when(spec)
    return Param(
        name=str(spec["name"]),
        kind=kind,
        default=spec.get("default"),
        min=_float(spec.get("min"), -math.inf),
        max=_float(spec.get("max"), math.inf),
        min_exclusive=bool(spec.get("min_exclusive", False)),
        max_exclusive=bool(spec.get("max_exclusive", False)),
        unit=str(spec.get("unit") or ""),
        doc=str(spec.get("doc") or ""),
        choices=[str(c) for c in (spec.get("choices") or [])],
        subtype=str(spec.get("subtype") or "color"),
        fields=[param_from_spec(f) for f in (spec.get("fields") or [])],
        when_param=when_param,
        when_values=when_values,
    )


def read_models(bxdf):
    """{model name: Model} in the registry's order."""
    return {name: Model(name=name, params=[param_from_spec(s) for s in specs],
                        doc=bxdf.model_doc(name))
            for name, specs in bxdf.models().items()}
