"""Shared fixtures for the Python tests of the `bxdf` module.

Run with the build tree's package on the path: PYTHONPATH=build/python python3 -m pytest tests/python
"""

import numpy as np
import pytest

try:
    import bxdf
except ImportError as exc:  # pragma: no cover - a set-up error, reported plainly
    raise ImportError(
        "cannot import bxdf: build it (cmake --build build) and run pytest with "
        "PYTHONPATH=build/python, using /usr/bin/python3"
    ) from exc


def model_variants():
    """(id, name, params) for every registered model: its defaults, plus each choice of each
    enum parameter with the others at their defaults. Generated from bxdf.models(), so a new
    model is tested as soon as it is registered."""
    out = []
    for name, specs in bxdf.models().items():
        out.append((f"{name}-defaults", name, {}))
        for spec in specs:
            if spec["kind"] != "enum":
                continue
            for choice in spec["choices"]:
                if choice != spec["default"]:
                    out.append((f"{name}-{spec['name']}={choice}", name, {spec["name"]: choice}))
    return out


VARIANTS = model_variants()


@pytest.fixture(params=VARIANTS, ids=[v[0] for v in VARIANTS])
def variant(request):
    """A model made from one entry of model_variants()."""
    _, name, params = request.param
    return bxdf.make(name, **params)


def is_delta(model):
    return "specular" in model.flags and not ({"diffuse", "glossy"} & model.flags)


def random_directions(rng, n, lower_fraction=0.3):
    """n unit directions, uniformly over the sphere but with about `lower_fraction` of them
    below the horizon (z < 0)."""
    v = rng.normal(size=(n, 3))
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    v[:, 2] = np.abs(v[:, 2])
    v[rng.random(n) < lower_fraction, 2] *= -1.0
    return v.astype(np.float32)


def awkward_directions():
    """Directions a model must survive: zero, unnormalised, grazing, below the horizon, tiny,
    huge, non-finite."""
    return np.array(
        [
            [0, 0, 0],
            [0, 0, 1],
            [0, 0, -1],
            [0, 0, 5e-8],
            [1, 0, 0],
            [0, 1, 0],
            [1e-30, 0, 1e-30],
            [3e30, 2e30, 1e30],
            [0.3, -0.2, 7.0],
            [0.6, 0.0, -0.8],
            [np.nan, 0, 1],
            [np.inf, 0, 1],
            [0, -np.inf, 0],
        ],
        dtype=np.float32,
    )


@pytest.fixture
def rng():
    return np.random.default_rng(12345)
