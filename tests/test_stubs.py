"""irisgl ships type information (py.typed and irisgl/__init__.pyi, written
by ``python -m irisgl.stubgen`` from the C declarations of
irisgl/prototypes.py), so an editor shows each call's C declaration."""
import ast
import inspect
import tomllib
from pathlib import Path

import irisgl
from irisgl import prototypes, stubgen
from irisgl._current import API, NOT_EMULATED

PKG = Path(irisgl.__file__).parent
ROOT = PKG.parent


def _stub():
    return ast.parse((PKG / "__init__.pyi").read_text())


def test_the_stub_is_what_stubgen_writes():
    assert (PKG / "__init__.pyi").read_text() == stubgen.render(), \
        "irisgl/__init__.pyi is stale: run python -m irisgl.stubgen"


def test_py_typed_and_the_stub_are_package_data():
    assert (PKG / "py.typed").is_file()
    conf = tomllib.loads((ROOT / "pyproject.toml").read_text())
    data = conf["tool"]["setuptools"]["package-data"]["irisgl"]
    assert "py.typed" in data and "*.pyi" in data


def test_every_name_of_the_star_import_is_in_the_stub():
    tree = _stub()
    defined = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            defined.add(node.name)
        elif isinstance(node, ast.Assign):
            defined.update(t.id for t in node.targets if isinstance(t, ast.Name))
        elif isinstance(node, ast.AnnAssign):
            defined.add(node.target.id)
    assert set(irisgl.__all__) <= defined


def test_every_provided_call_has_its_c_declaration():
    calls = [n for n in irisgl.__all__ if callable(getattr(irisgl, n))
             and not isinstance(getattr(irisgl, n), type)]
    missing = [n for n in calls if API.get(n, ("",))[0] != NOT_EMULATED
               and n not in prototypes.PROTOTYPES]
    assert missing == []
    docs = {f.name: ast.get_docstring(f) for f in _stub().body if isinstance(f, ast.FunctionDef)}
    for n in calls:
        if n in prototypes.PROTOTYPES:
            assert docs[n].startswith("C: " + prototypes.PROTOTYPES[n]), n


def test_c_types_become_python_annotations():
    funcs = {f.name: f for f in _stub().body if isinstance(f, ast.FunctionDef)}

    def sig(name):
        f = funcs[name]
        return ([(a.arg, ast.unparse(a.annotation)) for a in f.args.args],
                ast.unparse(f.returns))

    # C argument order and the header's type names
    assert sig("lookat") == ([("vx", "Coord"), ("vy", "Coord"), ("vz", "Coord"),
                              ("px", "Coord"), ("py", "Coord"), ("pz", "Coord"),
                              ("twist", "Angle")], "None")
    assert sig("pnt2s") == ([("x", "Scoord"), ("y", "Scoord")], "None")
    # pointers C fills come back after the C result (docs/porting.md, Results)
    assert sig("qread") == ([], "tuple[int, int]")
    assert sig("getsize") == ([], "tuple[int, int]")
    assert sig("getmcolor") == ([("i", "Colorindex")], "tuple[int, int, int]")
    assert sig("winopen")[1] == "int" and sig("genobj")[1] == "Object"
    # an array C fills is an optional trailing argument
    assert sig("lrectread")[0][-1] == ("parray", "ArrayLike | None")
    assert ast.unparse(funcs["blendcolor"].returns) == "NoReturn"      # not emulated


def test_stub_parameters_follow_the_python_functions():
    """Each stub keeps the Python function's parameter names, so a keyword
    call checked against the stub is a call the function takes."""
    funcs = {f.name: f for f in _stub().body if isinstance(f, ast.FunctionDef)}
    for name, f in funcs.items():
        fn = getattr(irisgl, name)
        params = [p.name for p in inspect.signature(fn).parameters.values()
                  if p.kind == p.POSITIONAL_OR_KEYWORD]
        if params:
            assert [a.arg for a in f.args.args] == params, name
