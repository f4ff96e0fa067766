"""The package itself: public names, docstrings, and type stubs that cover them."""

import ast
import os

import bxdf


def test_every_public_name_has_a_docstring():
    for name in bxdf.__all__:
        obj = getattr(bxdf, name)
        assert obj.__doc__ and len(obj.__doc__.strip()) > 20, name
    for name in ("f", "pdf", "sample_f", "rho", "rho_hh", "params", "flags", "name"):
        assert getattr(bxdf.Model, name).__doc__, name
    assert "ValueError" in bxdf.make.__doc__ and "lobes" in bxdf.make.__doc__
    assert bxdf.__doc__


def test_stubs_declare_every_public_name():
    path = os.path.join(os.path.dirname(bxdf.__file__), "__init__.pyi")
    assert os.path.exists(os.path.join(os.path.dirname(bxdf.__file__), "py.typed"))
    tree = ast.parse(open(path).read())
    declared = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    assert set(bxdf.__all__) <= declared, set(bxdf.__all__) - declared
    model = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "Model")
    methods = {n.name for n in model.body if isinstance(n, ast.FunctionDef)}
    public = {n for n in dir(bxdf.Model) if not n.startswith("_")}
    assert public <= methods, public - methods
