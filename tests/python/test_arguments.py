"""A call that pybind11 refuses names the argument and what was wrong with it (issue 15, "Bad
input": "Python exceptions naming the array, the row and the problem"), for every public function
and method: each parameter whose annotation can be judged is given a value of the wrong type while
the others get values of the right type, and the message must name that parameter."""

import numpy as np
import pytest

import limsurf
from limsurf import _arguments

WRONG = {"str": 3, "int": "x", "float": "x", "bool": "x", "limsurf._limsurf.Mesh": np.zeros((3, 3)), "os.PathLike": 3,
         "function": 3, "sequence": 3, "dict": [1.0]}


def _right_values(mesh, basis):
    return {"str": "x", "int": 1, "float": 1.0, "bool": False, "handle": None, "object": None,
            "limsurf._limsurf.Mesh": mesh, "limsurf._limsurf.LimitBasis": basis, "os.PathLike": "x",
            "function": abs, "sequence": [], "dict": {}}


def _right(annotation, right):
    if annotation.startswith("Optional["):
        return None
    if annotation.startswith(("List[", "Sequence[")):
        return []
    if annotation.startswith("Dict["):
        return {}
    if annotation in right:
        return right[annotation]
    raise LookupError(annotation)


def _callables(mesh, basis, geodesics, evaluator):
    for name in limsurf.__all__:
        value = getattr(limsurf, name)
        if callable(value) and not isinstance(value, type) and name != "subdivide":
            yield name, value, getattr(limsurf._limsurf, name).__doc__, ()
    yield "subdivide", limsurf.subdivide, limsurf._limsurf.subdivide.__doc__, ()
    for instance in (mesh, basis, geodesics, evaluator):
        cls = type(instance)
        for name, attribute in vars(cls).items():
            if name.startswith("_") or isinstance(attribute, property):
                continue
            yield f"{cls.__name__}.{name}", getattr(instance, name), attribute.__wrapped__.__doc__, (instance,)


def _signatures(doc):
    """The parameter lists of each overload that the docstring shows."""
    signatures = _arguments.docstring_signatures(doc)
    assert signatures and None not in signatures, f"cannot read a signature from {doc.splitlines()[0]!r}"
    return signatures


def test_every_refused_argument_is_named(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("cube"))
    basis = limsurf.LimitBasis(mesh, "catmull-clark")
    geodesics = limsurf.HeatGeodesics(mesh, "catmull-clark", method="dec")
    evaluator = limsurf.ShapeEvaluator(mesh, "catmull-clark")
    right = _right_values(mesh, basis)
    checked = set()
    for qualified, function, doc, bound in _callables(mesh, basis, geodesics, evaluator):
        short = qualified.split(".")[-1]
        signatures = _signatures(doc)
        for parameters in signatures:
            parameters = parameters[len(bound):]  # self is bound already
            try:
                good = {p: _right(a, right) for p, a, has_default, _ in parameters if not has_default}
            except LookupError:
                continue  # a required parameter of a type this test cannot make
            for parameter, annotation, _, keyword_only in parameters:
                if annotation not in WRONG:
                    continue
                kwargs = dict(good)
                kwargs[parameter] = WRONG[annotation]
                with pytest.raises(TypeError) as refused:
                    function(**kwargs)
                message = str(refused.value)
                if len(signatures) == 1:
                    assert message.startswith(f"{short}(): argument '{parameter}' must be "), (qualified, message)
                else:  # each overload says why it does not take the call
                    assert message.startswith(f"{short}(): no overload takes these arguments:"), (qualified, message)
                    assert f"argument '{parameter}' must be " in message, (qualified, message)
                checked.add(qualified)
    # all 58 callables but the seven whose parameters are only arrays (handle) or none at all:
    # LimitBasis.has_limit_surface, .limit_positions, .vertex_limit_matrix, HeatGeodesics.distance,
    # .source_values, Mesh.with_positions, rigid_body_modes
    assert len(checked) == 51, sorted(checked)


def test_the_message_says_what_was_given_and_how_to_fix_it(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("cube"))
    with pytest.raises(TypeError, match=r"^volume\(\): argument 'mesh' must be limsurf\.Mesh, got numpy\.ndarray "
                                        r"\(8, 3\) float64 \(make one with limsurf\.Mesh\(V, F\)"):
        limsurf.volume(mesh.V, "catmull-clark")
    with pytest.raises(TypeError, match=r"^subdivide\(\): argument 'levels' must be int, got float 2\.0\n"
                                        r"    subdivide\(mesh: limsurf\.Mesh, scheme: str, levels: int = 1"):
        limsurf.subdivide(mesh, "loop", 2.0)
    with pytest.raises(TypeError, match=r"^volume\(\): unexpected keyword argument 'gradiant' \(it takes: mesh, scheme, gradient,"):
        limsurf.volume(mesh, "catmull-clark", gradiant=True)
    with pytest.raises(TypeError, match=r"^volume\(\): argument 'scheme' given twice"):
        limsurf.volume(mesh, "catmull-clark", scheme="loop")
    with pytest.raises(TypeError, match=r"^Mesh\(\): missing argument 'F'"):
        limsurf.Mesh(mesh.V)
    with pytest.raises(TypeError, match=r"^LimitBasis\(\): takes at most 2 positional arguments \(mesh, scheme\), got 3"):
        limsurf.LimitBasis(mesh, "catmull-clark", "bilinear")
    with pytest.raises(TypeError, match=r"^read_mesh\(\): argument 'path' must be os\.PathLike, got str 'cube\\x00\.obj' "
                                        r"\(a path cannot hold a NUL character\)"):
        limsurf.read_mesh("cube\0.obj")


def test_a_list_element_of_the_wrong_type_is_named_by_its_index():
    parameters = _arguments._parameters("sources: List[int], weights: Optional[List[Tuple[int, float]]] = None")
    classes = {}
    assert _arguments._problem(parameters, ([0, 1, 2.5],), {}, classes) == "argument 'sources[2]' must be int, got float 2.5"
    assert _arguments._problem(parameters, ([0],), {"weights": [(1, 0.5), (2, "a")]}, classes) == (
        "argument 'weights[1][1]' must be float, got str 'a'")
    assert _arguments._problem(parameters, ([0],), {"weights": None}, classes) is None


def test_what_cannot_be_judged_keeps_pybind11s_message():
    refusal = ("f(): incompatible function arguments. The following argument types are supported:\n"
               "    1. (x: numpy.ndarray[numpy.float64[3, 1]]) -> None\n\nInvoked with: 'a'")
    assert _arguments._explain(refusal, ("a",), {}, {}) is None
    assert _arguments._explain("f() takes 2 arguments", (), {}, {}) is None


def test_a_call_that_converts_is_untouched(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("cube"))
    assert limsurf.volume(mesh, "catmull-clark") == limsurf._limsurf.volume(mesh, "catmull-clark")
    with pytest.raises(limsurf.InputError, match="unknown scheme"):
        limsurf.volume(mesh, "bogus")
