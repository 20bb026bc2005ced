"""limsurf: exact computation on subdivision surfaces.

Control meshes in and out as numpy arrays, subdivision with its sparse operators (scipy), the exact
limit surface and its derivatives and curvatures vectorised over points, area, exact enclosed
volume, moments, Subdivision Exterior Calculus operators, and Galerkin plates and shells on the limit
surface — the C++ library's numbers, identical to the `limsurf` command's. Tutorial: docs/guide/python.md.

    >>> import limsurf
    >>> mesh = limsurf.read_mesh("data/meshes/cube.obj")
    >>> limsurf.volume(mesh, "catmull-clark")          # exact, trilinear forms
"""
from ._limsurf import (
    Error,
    HeatGeodesics,
    InputError,
    LimitBasis,
    Mesh,
    MeshWarning,
    NumericalError,
    ShapeEvaluator,
    TopologyError,
    UnsupportedError,
    __version__,
    decompose_shapes,
    design_vector_field,
    eigen_analysis,
    elasticity,
    exterior_derivatives,
    feasible_subdominant_range,
    galerkin_load,
    geodesic_distance,
    harmonic_basis,
    hodge_decomposition,
    info,
    inner_products,
    laplace_beltrami,
    measure,
    minimize_membrane,
    one_form_vectors,
    one_ring_spectrum,
    operators,
    parameterize,
    plate,
    plate_bending_matrix,
    poisson,
    polyhedral_volumes,
    quadratic_shape_errors,
    read_mesh,
    rectangle_plate_deflection,
    render,
    reverse_catmull_clark,
    rigid_body_modes,
    self_intersections,
    shape_functionals,
    shape_hessian,
    shell,
    shell_stiffness,
    submesh,
    tessellate,
    tune_weights,
    tuned_vertex_weights,
    volume,
    weights_for_subdominant,
    write_glb,
    write_mesh,
)
from ._limsurf import subdivide as _subdivide
from . import _arguments, _limsurf

__all__ = [
    "Error",
    "HeatGeodesics",
    "InputError",
    "LimitBasis",
    "Mesh",
    "MeshWarning",
    "NumericalError",
    "ShapeEvaluator",
    "TopologyError",
    "UnsupportedError",
    "__version__",
    "decompose_shapes",
    "design_vector_field",
    "eigen_analysis",
    "elasticity",
    "exterior_derivatives",
    "feasible_subdominant_range",
    "galerkin_load",
    "geodesic_distance",
    "harmonic_basis",
    "hodge_decomposition",
    "info",
    "inner_products",
    "laplace_beltrami",
    "measure",
    "minimize_membrane",
    "one_form_vectors",
    "one_ring_spectrum",
    "operators",
    "parameterize",
    "plate",
    "plate_bending_matrix",
    "poisson",
    "polyhedral_volumes",
    "quadratic_shape_errors",
    "read_mesh",
    "rectangle_plate_deflection",
    "render",
    "reverse_catmull_clark",
    "rigid_body_modes",
    "self_intersections",
    "shape_functionals",
    "shape_hessian",
    "shell",
    "shell_stiffness",
    "subdivide",
    "submesh",
    "tessellate",
    "tune_weights",
    "tuned_vertex_weights",
    "volume",
    "weights_for_subdominant",
    "write_glb",
    "write_mesh",
]


def subdivide(*args, **kwargs):
    """Refines a mesh uniformly: ``subdivide(mesh, scheme, levels=1, ...)`` or, from arrays,
    ``subdivide(V, F, scheme, levels=1, ...)``.

    Returns the finest :class:`Mesh`; with ``operators=True`` (or ``forms=True``) a pair
    ``(mesh, ops)`` with the scipy CSR operators ``ops["S0"]`` (and ``"S1"``, ``"S2"``,
    ``"steps"``); with ``topology=False`` the finest ``(V, F)`` arrays instead of the Mesh (its face
    list, without a Mesh's edge and one-ring tables; with operators, ``((V, F), ops)``, and no level's
    tables are kept past the control mesh). See ``limsurf._limsurf.subdivide`` for every keyword.
    """
    if args and not isinstance(args[0], Mesh):
        if len(args) < 2:
            raise TypeError("subdivide(V, F, scheme, levels=1): F is missing")
        args = (Mesh(args[0], args[1]),) + tuple(args[2:])
    return _subdivide(*args, **kwargs)


def _explain_refused_calls():
    """Every public function and method wrapped so that a call pybind11 refuses names the argument
    (see _arguments.py); the same objects otherwise, the same docstrings."""
    classes = {n: c for n, c in vars(_limsurf).items() if isinstance(c, type)}
    namespace = globals()
    for name in __all__:
        value = namespace[name]
        if type(value).__name__ == "builtin_function_or_method":
            namespace[name] = _arguments.explained(value, classes)
        elif isinstance(value, type) and value.__module__ == _limsurf.__name__ and not issubclass(value, BaseException):
            _arguments.explain_methods(value, classes)
    namespace["_subdivide"] = _arguments.explained(_subdivide, classes)


_explain_refused_calls()
