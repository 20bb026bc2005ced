# Type stubs of the limsurf Python module (docs/guide/python.md). Keep in step with python/src/*.cpp:
# tests/python/test_stubs.py checks that every public name has a stub and the other way round.
import os
from typing import Callable, Literal, TypedDict, overload

import numpy as np
import numpy.typing as npt
import scipy.sparse

__version__: str

Scheme = Literal["catmull-clark", "loop", "doo-sabin", "c2g0", "bilinear", "linear"]
LimitScheme = Literal["catmull-clark", "loop", "doo-sabin", "c2g0"]
Boundary = Literal["none", "edge-only", "edge-and-corner"]
Creasing = Literal["uniform", "chaikin"]
Triangles = Literal["catmull-clark", "smooth"]
Method = Literal["dec", "decsnap", "sec", "secsnap"]
ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.float64]
IndexArray = npt.NDArray[np.int32]
PathLike = str | os.PathLike[str]
SurfaceFunction = Callable[[FloatArray], ArrayLike]

class Error(RuntimeError): ...
class InputError(Error, ValueError): ...
class TopologyError(Error, ValueError): ...
class NumericalError(Error, ArithmeticError): ...
class UnsupportedError(Error, NotImplementedError): ...
class MeshWarning(UserWarning): ...

class Mesh:
    def __init__(self, V: ArrayLike, F: ArrayLike | list[ArrayLike], *, creases: ArrayLike | None = None,
                 corners: ArrayLike | None = None, holes: ArrayLike | None = None, boundary: Boundary | None = None,
                 creasing: Creasing | None = None, triangles: Triangles | None = None,
                 isolated: Literal["error", "drop"] = "error") -> None: ...
    @property
    def V(self) -> FloatArray: ...
    @property
    def F(self) -> IndexArray | list[IndexArray]: ...
    @property
    def face_offsets(self) -> IndexArray: ...
    @property
    def face_vertices(self) -> IndexArray: ...
    @property
    def edges(self) -> IndexArray: ...
    @property
    def num_vertices(self) -> int: ...
    @property
    def num_edges(self) -> int: ...
    @property
    def num_faces(self) -> int: ...
    @property
    def genus(self) -> int: ...
    @property
    def is_closed(self) -> bool: ...
    @property
    def boundary_loops(self) -> list[IndexArray]: ...
    @property
    def creases(self) -> FloatArray: ...
    @property
    def corners(self) -> FloatArray: ...
    @property
    def file(self) -> str | None: ...
    def with_positions(self, V: ArrayLike) -> Mesh: ...

@overload
def read_mesh(path: PathLike, *, isolated: Literal["error", "drop"] = "drop", groups: Literal[False] = False) -> Mesh: ...
@overload
def read_mesh(path: PathLike, *, isolated: Literal["error", "drop"] = "drop",
              groups: Literal[True]) -> tuple[Mesh, IndexArray, list[str]]: ...
def write_mesh(path: PathLike, mesh: Mesh, *, ply_encoding: Literal["ascii", "binary-le", "binary-be"] = "ascii") -> None: ...
def info(mesh: Mesh) -> dict[str, object]: ...
def submesh(mesh: Mesh, keep: ArrayLike) -> tuple[Mesh, IndexArray, IndexArray]: ...

class SubdivisionOperators(TypedDict, total=False):
    S0: scipy.sparse.csr_matrix
    S1: scipy.sparse.csr_matrix
    S2: scipy.sparse.csr_matrix
    steps: list[dict[str, scipy.sparse.csr_matrix]]

@overload
def subdivide(mesh: Mesh, scheme: Scheme, levels: int = 1, *, operators: Literal[False] = False,
              forms: Literal[False] = False, boundary: Boundary | None = None, creasing: Creasing | None = None,
              triangles: Triangles | None = None, threads: int = 0, topology: Literal[True] = True) -> Mesh: ...
@overload
def subdivide(mesh: Mesh, scheme: Scheme, levels: int = 1, *, operators: Literal[False] = False,
              forms: Literal[False] = False, boundary: Boundary | None = None, creasing: Creasing | None = None,
              triangles: Triangles | None = None, threads: int = 0,
              topology: Literal[False]) -> tuple[FloatArray, IndexArray | list[IndexArray]]: ...
@overload
def subdivide(mesh: Mesh, scheme: Scheme, levels: int = 1, *, operators: bool = False, forms: bool = False,
              boundary: Boundary | None = None, creasing: Creasing | None = None,
              triangles: Triangles | None = None, threads: int = 0,
              topology: Literal[False]) -> tuple[FloatArray, IndexArray | list[IndexArray]] | tuple[
                  tuple[FloatArray, IndexArray | list[IndexArray]], SubdivisionOperators]: ...
@overload
def subdivide(mesh: Mesh, scheme: Scheme, levels: int = 1, *, operators: bool = False, forms: bool = False,
              boundary: Boundary | None = None, creasing: Creasing | None = None,
              triangles: Triangles | None = None, threads: int = 0,
              topology: bool = True) -> Mesh | tuple[Mesh, SubdivisionOperators] | tuple[
                  FloatArray, IndexArray | list[IndexArray]] | tuple[
                  tuple[FloatArray, IndexArray | list[IndexArray]], SubdivisionOperators]: ...
@overload
def subdivide(V: ArrayLike, F: ArrayLike | list[ArrayLike], scheme: Scheme, levels: int = 1, *,
              operators: bool = False, forms: bool = False, boundary: Boundary | None = None,
              creasing: Creasing | None = None, triangles: Triangles | None = None,
              threads: int = 0, topology: bool = True) -> Mesh | tuple[Mesh, SubdivisionOperators] | tuple[
                  FloatArray, IndexArray | list[IndexArray]] | tuple[
                  tuple[FloatArray, IndexArray | list[IndexArray]], SubdivisionOperators]: ...

class LimitEvaluation(TypedDict, total=False):
    position: FloatArray
    du: FloatArray
    dv: FloatArray
    duu: FloatArray
    duv: FloatArray
    dvv: FloatArray
    normal: FloatArray
    mean_curvature: FloatArray
    gaussian_curvature: FloatArray
    k1: FloatArray
    k2: FloatArray
    curvature_defined: npt.NDArray[np.bool_]

class LimitBasis:
    def __init__(self, mesh: Mesh, scheme: LimitScheme, *, boundary: Boundary | None = None,
                 creasing: Creasing | None = None, triangles: Triangles | None = None) -> None: ...
    @property
    def num_ptex_faces(self) -> int: ...
    @property
    def num_vertices(self) -> int: ...
    @property
    def scheme(self) -> str: ...
    @property
    def domain(self) -> Literal["quad", "triangle"]: ...
    @property
    def mesh(self) -> Mesh: ...
    def ptex_face(self, p: int) -> tuple[int, int]: ...
    def has_limit_surface(self) -> npt.NDArray[np.bool_]: ...
    def evaluate(self, faces: ArrayLike, u: ArrayLike, v: ArrayLike, order: Literal[0, 1, 2] = 2, *,
                 X: ArrayLike | None = None, threads: int = 0, frames: bool = True,
                 out: LimitEvaluation | None = None) -> LimitEvaluation: ...
    def weights(self, faces: ArrayLike, u: ArrayLike, v: ArrayLike,
                order: Literal[0, 1, 2] = 0) -> dict[str, scipy.sparse.csr_matrix]: ...
    def patch(self, face: int, u: float, v: float, *, X: ArrayLike | None = None,
              points: bool = True) -> dict[str, object] | None: ...
    def vertex_limit_matrix(self) -> scipy.sparse.csr_matrix: ...
    def limit_positions(self, *, X: ArrayLike | None = None) -> FloatArray: ...
    def quadrature_samples(self, *, degree: int = 8, tiles: int = 0) -> dict[str, npt.NDArray[np.generic]]: ...

def measure(mesh: Mesh, scheme: LimitScheme, *, degree: int = 12, tiles: int = 10, boundary: Boundary | None = None,
            creasing: Creasing | None = None, triangles: Triangles | None = None) -> dict[str, object]: ...
@overload
def volume(mesh: Mesh, scheme: LimitScheme, *, gradient: Literal[False] = False, X: ArrayLike | None = None,
           boundary: Boundary | None = None, creasing: Creasing | None = None,
           triangles: Triangles | None = None) -> float: ...
@overload
def volume(mesh: Mesh, scheme: LimitScheme, *, gradient: Literal[True], X: ArrayLike | None = None,
           boundary: Boundary | None = None, creasing: Creasing | None = None,
           triangles: Triangles | None = None) -> tuple[float, FloatArray]: ...

class PolyhedralVolume(TypedDict):
    level: int
    faces: int
    volume: float

def polyhedral_volumes(mesh: Mesh, scheme: Scheme, *, levels: int = 3, max_faces: int = 4194304,
                       boundary: Boundary | None = None, creasing: Creasing | None = None,
                       triangles: Triangles | None = None) -> list[PolyhedralVolume]: ...

def exterior_derivatives(mesh: Mesh) -> tuple[scipy.sparse.csr_matrix, scipy.sparse.csr_matrix]: ...
def inner_products(mesh: Mesh, scheme: LimitScheme, *, method: Method = "sec", level: int | None = None,
                   lumped: bool = False, boundary: Boundary | None = None, creasing: Creasing | None = None,
                   triangles: Triangles | None = None) -> dict[str, scipy.sparse.csr_matrix]: ...
def operators(mesh: Mesh, scheme: LimitScheme, *, method: Method = "sec", level: int | None = None,
              lumped: bool = False, boundary: Boundary | None = None, creasing: Creasing | None = None,
              triangles: Triangles | None = None) -> dict[str, scipy.sparse.csr_matrix]: ...
def poisson(mesh: Mesh, scheme: LimitScheme, rhs: SurfaceFunction | ArrayLike, *,
            method: Method | Literal["iga"] = "sec", level: int | None = None, lumped: bool = False,
            degree: int | None = None, tiles: int | None = None,
            boundary_values: SurfaceFunction | ArrayLike | float | None = None,
            reference_level: int | None = None, max_memory: int | None = None, boundary: Boundary | None = None,
            creasing: Creasing | None = None, triangles: Triangles | None = None,
            threads: int = 0) -> dict[str, object]: ...

def parameterize(mesh: Mesh, scheme: Literal["loop", "catmull-clark"], *, method: Method | Literal["iga"] = "sec",
                 level: int | None = None,
                 boundary: Literal["free", "circle"] = "free", reference_level: int | None = None,
                 max_memory: int | None = None, degree: int = 6, tiles: int = 3, threads: int = 0,
                 boundary_rule: Boundary | None = None, creasing: Creasing | None = None,
                 triangles: Triangles | None = None) -> dict[str, object]: ...
def one_form_vectors(mesh: Mesh, scheme: Literal["loop", "catmull-clark"], w: ArrayLike, *, level: int = 2,
                     boundary: Boundary | None = None, creasing: Creasing | None = None,
                     triangles: Triangles | None = None) -> dict[str, object]: ...
def design_vector_field(mesh: Mesh, scheme: Literal["loop", "catmull-clark"], *,
                        sources: list[tuple[int, float] | tuple[int, float, float]] = ...,
                        sinks: list[tuple[int, float] | tuple[int, float, float]] = ...,
                        vortices: list[tuple[int, float] | tuple[int, float, float]] = ...,
                        strokes: list[tuple[list[int], float] | tuple[list[int], float, float]] = ...,
                        weight: float = 1000.0, method: Method = "sec", level: int | None = None,
                        vertex_mass: Literal["exact", "lumped"] = "exact", sample_level: int = 2,
                        reference_level: int | None = None, boundary: Boundary | None = None,
                        creasing: Creasing | None = None, triangles: Triangles | None = None) -> dict[str, object]: ...
def hodge_decomposition(mesh: Mesh, scheme: Literal["loop", "catmull-clark"], w: ArrayLike | None = None, *,
                        random: int | None = None, method: Method = "sec", level: int | None = None, basis: bool = True,
                        reference_level: int | None = None, boundary: Boundary | None = None,
                        creasing: Creasing | None = None, triangles: Triangles | None = None) -> dict[str, object]: ...
def harmonic_basis(mesh: Mesh, scheme: Literal["loop", "catmull-clark"], *, method: Method = "sec",
                   level: int | None = None, seed: int = 1, boundary: Boundary | None = None,
                   creasing: Creasing | None = None, triangles: Triangles | None = None) -> dict[str, object]: ...
def geodesic_distance(mesh: Mesh, scheme: Literal["loop", "catmull-clark"], sources: int | list[int], *,
                      method: Method | Literal["iga"] = "sec", level: int | None = None, degree: int | None = None,
                      tiles: int | None = None,
                      gradient: Literal["auto", "limit", "subdivided"] = "auto", gradient_level: int | None = None,
                      gradient_degree: int = 2, time_factor: float = 1.0, reference_level: int | None = None,
                      max_memory: int | None = None,
                      boundary: Boundary | None = None, creasing: Creasing | None = None,
                      triangles: Triangles | None = None) -> dict[str, object]: ...

class HeatGeodesics:
    def __init__(self, mesh: Mesh, scheme: Literal["loop", "catmull-clark"], *,
                 method: Method | Literal["iga"] = "sec", level: int | None = None, degree: int | None = None,
                 tiles: int | None = None,
                 gradient: Literal["auto", "limit", "subdivided"] = "auto",
                 gradient_level: int | None = None, gradient_degree: int = 2, time_factor: float = 1.0,
                 boundary: Boundary | None = None, creasing: Creasing | None = None,
                 triangles: Triangles | None = None) -> None: ...
    def distance(self, sources: int | list[int]) -> FloatArray: ...
    def distances(self, source_sets: list[int | list[int]]) -> FloatArray: ...
    def source_values(self, phi: ArrayLike, sources: int | list[int]) -> FloatArray: ...
    @property
    def time_step(self) -> float: ...
    @property
    def mean_edge_length(self) -> float: ...
    @property
    def max_edge_length(self) -> float: ...
    @property
    def gradient(self) -> Literal["control", "limit", "subdivided"]: ...
    @property
    def gradient_level(self) -> int | None: ...
    @property
    def setup_seconds(self) -> float: ...
    @property
    def factorisation_seconds(self) -> float: ...

class Tessellation(TypedDict, total=False):
    positions: FloatArray
    normals: FloatArray
    triangles: IndexArray
    faces: IndexArray
    u: FloatArray
    v: FloatArray
    mean_curvature: FloatArray
    gaussian_curvature: FloatArray
    estimated: npt.NDArray[np.bool_]
    value_weights: scipy.sparse.csr_matrix
    resolution: int

def tessellate(mesh: Mesh, scheme: LimitScheme, *, resolution: int = 0, curvature: bool = True,
               X: ArrayLike | None = None, threads: int = 0, boundary: Boundary | None = None,
               creasing: Creasing | None = None, triangles: Triangles | None = None) -> Tessellation: ...
def render(mesh: Mesh, scheme: LimitScheme,
           field: Literal["mean-curvature", "gaussian-curvature"] | ArrayLike | None = None, *,
           control_mesh: bool = False, isolines: int = 0, view: str | tuple[float, float] = "iso",
           size: tuple[int, int] = (1200, 900), resolution: int = 0, range: tuple[float, float] | None = None,
           colormap: Literal["viridis", "coolwarm"] = "viridis", supersampling: int = 2, color_bar: bool = True,
           output: PathLike | None = None, threads: int = 0, boundary: Boundary | None = None,
           creasing: Creasing | None = None, triangles: Triangles | None = None) -> dict[str, object]: ...
def write_glb(path: PathLike, positions: ArrayLike, triangles: ArrayLike, *, normals: ArrayLike | None = None,
              colors: ArrayLike | None = None, scalar: ArrayLike | None = None, scalar_name: str = "field") -> None: ...

FemScheme = Literal["catmull-clark", "loop"]
PlateSupport = Literal["simply", "clamped"]
PlateLoadName = Literal["uniform", "sinusoidal", "single-wave"]
ShellTerms = Literal["membrane-and-bending", "membrane", "bending"]
Vector3 = tuple[float, float, float] | ArrayLike
SupportSelection = Callable[[FloatArray], ArrayLike] | bool | ArrayLike
Traction = Callable[[FloatArray, FloatArray], ArrayLike]

class GalerkinMatrices(TypedDict):
    mass: scipy.sparse.csr_matrix
    stiffness: scipy.sparse.csr_matrix

def laplace_beltrami(mesh: Mesh, scheme: LimitScheme, *, degree: int = 8, tiles: int = 6,
                     boundary: Boundary | None = None, creasing: Creasing | None = None,
                     triangles: Triangles | None = None) -> GalerkinMatrices: ...
def galerkin_load(mesh: Mesh, scheme: LimitScheme, f: SurfaceFunction, *, degree: int = 8, tiles: int = 6,
                  boundary: Boundary | None = None, creasing: Creasing | None = None,
                  triangles: Triangles | None = None) -> FloatArray: ...
def plate_bending_matrix(mesh: Mesh, scheme: LimitScheme, *, E: float = 2e11, nu: float = 0.3, thickness: float = 0.1,
                         degree: int = 6, tiles: int = 6, boundary: Boundary | None = None,
                         creasing: Creasing | None = None, triangles: Triangles | None = None) -> scipy.sparse.csr_matrix: ...
def shell_stiffness(mesh: Mesh, scheme: LimitScheme, *, E: float = 1.0, nu: float = 0.3, thickness: float = 0.1,
                    terms: ShellTerms = "membrane-and-bending", degree: int = 6, tiles: int = 4,
                    boundary: Boundary | None = None, creasing: Creasing | None = None,
                    triangles: Triangles | None = None) -> scipy.sparse.csr_matrix: ...
def rigid_body_modes(V: Mesh | ArrayLike) -> FloatArray: ...
def rectangle_plate_deflection(a: float, b: float, x: float | ArrayLike, y: float | ArrayLike, *, D: float = 1.0,
                               p: float = 1.0, waves: tuple[int, int] | None = None,
                               series: Literal["levy", "navier"] = "levy",
                               tolerance: float = 1e-14) -> float | FloatArray: ...
def plate(mesh: Mesh, scheme: FemScheme, load: float | PlateLoadName | SurfaceFunction | ArrayLike, *,
          support: PlateSupport = "simply", E: float = 2e11, nu: float = 0.3, thickness: float = 0.1, levels: int = 0,
          pressure: float | None = None, degree: int = 6, tiles: int = 6,
          tuned: Literal["none", "cup", "saddle", "auto"] = "none",
          decide_level: int | None = None) -> dict[str, object]: ...
def shell(mesh: Mesh, scheme: FemScheme, *, levels: int = 0, E: float = 1.0, nu: float = 0.3, thickness: float = 0.1,
          gravity: float = 0.0, pressure: float = 0.0, traction: Traction | None = None,
          point_loads: list[tuple[Vector3, Vector3]] = ..., supports: list[tuple[SupportSelection, str]] = ...,
          probes: list[Vector3] | ArrayLike = ..., interpolate: bool = False, surface: SurfaceFunction | None = None,
          degree: int = 6, tiles: int = 4) -> dict[str, object]: ...

# Biomembrane shapes (docs/guide/membrane.md).
MembraneScheme = Literal["c2g0", "loop", "catmull-clark"]
MembraneHessian = Literal["limited-memory", "exact"]
ShapeFunctionalName = Literal["area", "volume", "mean_curvature", "willmore", "gaussian", "harmonic"]

class ShapeFunctionals(TypedDict, total=False):
    area: float
    volume: float
    mean_curvature: float
    willmore: float
    gaussian: float
    harmonic: float
    reduced_volume: float
    reduced_mean_curvature: float
    helfrich: float
    volume_is_exact: bool
    samples: int
    sum_factorised_elements: int
    gradient: dict[str, FloatArray]

class MembraneIterationReport(TypedDict):
    stage: Literal["continuation", "shape", "regularization"]
    iteration: int
    objective: float
    constraint_violation: float
    dual_infeasibility: float
    step: float
    restoration: bool  # Ipopt's restoration phase; the regular iteration leaving it repeats its last number
    watchdog: bool  # a trial step of Ipopt's watchdog procedure (not tested by the filter)

@overload
def shape_functionals(mesh: Mesh, scheme: MembraneScheme, *, X: ArrayLike | None = None, gradients: bool = True,
                      spontaneous_curvature: float | None = None, degree: int = 8,
                      subdivide_near_extraordinary: int = 3, threads: int = 0,
                      sum_factorisation: bool = True) -> ShapeFunctionals: ...
@overload
def shape_functionals(V: ArrayLike, F: ArrayLike | list[ArrayLike], scheme: MembraneScheme, *,
                      X: ArrayLike | None = None, gradients: bool = True, spontaneous_curvature: float | None = None,
                      degree: int = 8, subdivide_near_extraordinary: int = 3, threads: int = 0,
                      sum_factorisation: bool = True) -> ShapeFunctionals: ...
@overload
def minimize_membrane(mesh: Mesh, scheme: MembraneScheme, *, area: float, volume: float | None = None,
                      reduced_volume: float | None = None, mean_curvature: float | None = None,
                      reduced_mean_curvature: float | None = None, spontaneous_curvature: float | None = None,
                      regularize_harmonic: float | None = None, max_iterations: int = 1000, tolerance: float = 1e-8,
                      objective_tolerance: float = 1e-7, hessian: MembraneHessian = "limited-memory",
                      regularization_hessian: MembraneHessian | None = None, continuation_steps: int = 1,
                      callback: Callable[[MembraneIterationReport], bool | None] | None = None, degree: int = 8,
                      subdivide_near_extraordinary: int = 3, threads: int = 0,
                      sum_factorisation: bool = True) -> dict[str, object]: ...
@overload
def minimize_membrane(V: ArrayLike, F: ArrayLike | list[ArrayLike], scheme: MembraneScheme, *, area: float,
                      volume: float | None = None, reduced_volume: float | None = None,
                      mean_curvature: float | None = None, reduced_mean_curvature: float | None = None,
                      spontaneous_curvature: float | None = None, regularize_harmonic: float | None = None,
                      max_iterations: int = 1000, tolerance: float = 1e-8,
                      objective_tolerance: float = 1e-7, hessian: MembraneHessian = "limited-memory",
                      regularization_hessian: MembraneHessian | None = None, continuation_steps: int = 1,
                      callback: Callable[[MembraneIterationReport], bool | None] | None = None, degree: int = 8,
                      subdivide_near_extraordinary: int = 3, threads: int = 0,
                      sum_factorisation: bool = True) -> dict[str, object]: ...

@overload
def shape_hessian(mesh: Mesh, scheme: MembraneScheme, coefficients: dict[ShapeFunctionalName, float], *,
                  X: ArrayLike | None = None, degree: int = 8, subdivide_near_extraordinary: int = 3,
                  threads: int = 0) -> scipy.sparse.csr_matrix: ...
@overload
def shape_hessian(V: ArrayLike, F: ArrayLike | list[ArrayLike], scheme: MembraneScheme,
                  coefficients: dict[ShapeFunctionalName, float], *, X: ArrayLike | None = None, degree: int = 8,
                  subdivide_near_extraordinary: int = 3, threads: int = 0) -> scipy.sparse.csr_matrix: ...

class SelfIntersections(TypedDict):
    intersects: bool
    intersecting_pairs: int
    control_faces: list[int]
    resolution: int
    triangles: int

@overload
def self_intersections(mesh: Mesh, scheme: Scheme, *, X: ArrayLike | None = None, resolution: int = 0,
                       threads: int = 0) -> SelfIntersections: ...
@overload
def self_intersections(V: ArrayLike, F: ArrayLike | list[ArrayLike], scheme: Scheme, *, X: ArrayLike | None = None,
                       resolution: int = 0, threads: int = 0) -> SelfIntersections: ...

class ShapeEvaluator:
    """The shape functionals of one closed mesh set up once, evaluated at any positions after."""
    @overload
    def __init__(self, mesh: Mesh, scheme: MembraneScheme, *, degree: int = 8, subdivide_near_extraordinary: int = 3,
                 threads: int = 0, sum_factorisation: bool = True) -> None: ...
    @overload
    def __init__(self, V: ArrayLike, F: ArrayLike | list[ArrayLike], scheme: MembraneScheme, *, degree: int = 8,
                 subdivide_near_extraordinary: int = 3, threads: int = 0, sum_factorisation: bool = True) -> None: ...
    def evaluate(self, X: ArrayLike | None = None, *, gradients: bool = True,
                 spontaneous_curvature: float | None = None) -> ShapeFunctionals: ...
    def hessian(self, coefficients: dict[ShapeFunctionalName, float],
                X: ArrayLike | None = None) -> scipy.sparse.csr_matrix: ...
    def self_intersections(self, X: ArrayLike | None = None, *, resolution: int = 0) -> SelfIntersections: ...
    @property
    def scheme(self) -> MembraneScheme: ...
    @property
    def num_vertices(self) -> int: ...
    @property
    def num_samples(self) -> int: ...
    @property
    def volume_is_exact(self) -> bool: ...
    @property
    def sum_factorised_elements(self) -> int: ...

# IGA-tuned Catmull–Clark weights (docs/guide/tune.md, docs/guide/python.md).
TuningShape = Literal["cup", "saddle"]
Constraint = Literal["exact", "relaxed", "none"]
# "lambda" is a keyword: the keys that hold it are declared in the functional syntax.
_TuningWeightsKeys = TypedDict("_TuningWeightsKeys", {"lambda": float, "alpha": float, "beta": float, "gamma": float,
                                                      "constraint": Constraint, "lambda3": float, "lambda4": float})
_TuningCurveLambda = TypedDict("_TuningCurveLambda", {"lambda": FloatArray})

class TuningWeights(_TuningWeightsKeys, total=False):
    """W: the weights (alpha, beta, gamma) of an extraordinary vertex, the constraint that fixed them and the
    one-ring eigenvalues (lambda, lambda3, lambda4); 'cup_error' and 'saddle_error' where computed."""
    cup_error: float
    saddle_error: float

class TuningCurve(_TuningCurveLambda):
    """The error curve over λ as columns (increasing λ), one entry per sample."""
    alpha: FloatArray
    beta: FloatArray
    gamma: FloatArray
    lambda3: FloatArray
    lambda4: FloatArray
    cup_error: FloatArray
    saddle_error: FloatArray
    constraint: list[Constraint]

class TuningResult(TypedDict):
    """The dict of `limsurf tune --json` (without 'command' and 'time_seconds'), the curve as columns."""
    valence: int
    shape: TuningShape
    quadrature_points: int
    tile_levels: int
    poisson_ratio: float
    feasible_range: tuple[float, float]
    search_range: tuple[float, float]
    protect_other_shape: bool
    protection_binds: bool
    tuned: TuningWeights
    unconstrained: TuningWeights
    classical: TuningWeights
    curve: TuningCurve

class ShapeErrors(TypedDict):
    cup: float
    saddle: float

class ShapeDecomposition(TypedDict):
    """The cup–saddle decomposition at one extraordinary vertex (§3.4)."""
    vertex: int
    valence: int
    k3: float
    k4: float
    k5: float
    ratio: float  # inf without a saddle part, nan where flat
    has_quadratic_part: bool  # False where P is flat there to rounding (k3 = k4 = k5 = 0)
    normal: FloatArray
    position: FloatArray
    tangents: FloatArray
    cup_dominates: bool

VertexWeights = tuple[float, float, float] | TuningWeights
TunedWeightsSpec = Literal["cup", "saddle", "catmull-clark"] | str | dict[str, dict[int, VertexWeights]] | None

def feasible_subdominant_range(valence: int) -> tuple[float, float]:
    """The interval (low, high) of subdominant eigenvalues λ with tuned weights at this valence."""
def one_ring_spectrum(valence: int, alpha: float | None = None, beta: float = 1.0, gamma: float = 1.0) -> TuningWeights:
    """The one-ring eigenvalues (lambda, lambda3, lambda4) of the weights; alpha None: Catmull–Clark's."""
def weights_for_subdominant(valence: int, lambda_: float) -> list[TuningWeights]:
    """The weights (one or two candidates, exact ones first) whose subdominant eigenvalue is lambda_."""
def quadratic_shape_errors(valence: int, alpha: float | None = None, beta: float = 1.0, gamma: float = 1.0, *,
                           quadrature: int = 4, tile_levels: int = 10, poisson_ratio: float = 0.3,
                           threads: int = 0) -> ShapeErrors:
    """The relative energy-norm errors (32) of the cup and the saddle with these weights."""
def tune_weights(valence: int, shape: TuningShape = "cup", *, quadrature: int = 4, tile_levels: int = 10,
                 poisson_ratio: float = 0.3, lambda_range: tuple[float, float] | None = None, samples: int = 61,
                 protect: bool = True, threads: int = 0) -> TuningResult:
    """The search in λ of `limsurf tune --json` (the curve as numpy columns)."""
def tuned_vertex_weights(valence: int, shape: TuningShape = "cup", *, quadrature: int = 4, tile_levels: int = 10,
                         poisson_ratio: float = 0.3, threads: int = 0) -> TuningWeights:
    """The tuned weights for the shape, λ rounded to three decimals as Table 1 prints it, with both errors."""
@overload
def decompose_shapes(mesh: Mesh, P: ArrayLike | None = None, *, weights: TunedWeightsSpec = None,
                     min_valence: int = 5, poisson_ratio: float = 0.3) -> list[ShapeDecomposition]:
    """The local cup–saddle decomposition of P at every extraordinary vertex of valence >= min_valence."""
@overload
def decompose_shapes(V: ArrayLike, F: ArrayLike | list[ArrayLike], P: ArrayLike | None = None, *,
                     weights: TunedWeightsSpec = None, min_valence: int = 5,
                     poisson_ratio: float = 0.3) -> list[ShapeDecomposition]: ...

# The eigen-analysis of a scheme at one extraordinary vertex (docs/guide/eigen.md, docs/eigen.md).
EigenScheme = Literal["catmull-clark", "loop", "doo-sabin", "c2g0"]

class Eigenvalue(TypedDict):
    value: complex
    frequency: int | None  # the Fourier block; None without rotational symmetry (a boundary vertex)
    algebraic: int
    geometric: int
    jordan_blocks: list[int]
    eigenvectors: npt.NDArray[np.complex128]  # size × geometric, over the neighbourhood

class CharacteristicMap(TypedDict, total=False):
    evaluated: bool
    reason: str  # when not evaluated
    min_jacobian: float
    max_jacobian: float
    winding_number: float
    samples: int  # those in the ring segment, where det DΦ is checked
    resolution: int
    positions: FloatArray  # every face's (resolution + 1)² or (resolution + 1)(resolution + 2)/2 points × 3, z = 0
    faces: IndexArray

class SmoothnessTest(TypedDict):
    checked: bool
    passed: bool | None  # None when not checked
    detail: str

class SchemeSpectrum(TypedDict):
    """`limsurf eigen --json`'s dict, with the local subdivision matrix S and its sectors."""
    scheme: EigenScheme
    valence: int
    boundary: bool
    rings: int
    size: int
    symmetry_residual: float
    dominant: float
    subdominant: float
    subdominant_multiplicity: int
    subsubdominant: float
    subsubdominant_multiplicity: int
    eigenvalues: list[Eigenvalue]
    characteristic_map: CharacteristicMap
    tests: dict[Literal["c1_spectrum", "c1", "bounded_curvature", "c2_necessary"], SmoothnessTest]
    S: FloatArray
    sector: IndexArray

def eigen_analysis(scheme: EigenScheme, valence: int, *, boundary: bool = False,
                   weights: VertexWeights | None = None, rings: int = 0) -> SchemeSpectrum:
    """The spectrum of the local subdivision matrix at one extraordinary vertex and the smoothness verdicts."""

# Plane elasticity and homogenisation (docs/guide/elasticity.md).
RectangleSide = Literal["left", "right", "bottom", "top"]

class ElasticityFields(TypedDict):
    positions: FloatArray
    triangles: IndexArray
    displacement: FloatArray
    strain: FloatArray
    stress: FloatArray
    von_mises: FloatArray
    material: IndexArray
    resolution: int

@overload
def elasticity(mesh: Mesh, *, E: float = 1.0, nu: float = 0.3, plane_stress: bool = False,
               boundary: Literal["periodic", "affine", "loaded"] = "periodic",
               macro_deformation: ArrayLike | None = None, face_material: ArrayLike | None = None,
               materials: list[tuple[float, float]] | None = None, levels: int = 0, quadrature: int = 6,
               effective_stiffness: bool = True, crease_interfaces: bool = False,
               clamp: tuple[RectangleSide, ...] | list[RectangleSide] = (),
               tractions: list[tuple[RectangleSide, tuple[float, float]]] | tuple[()] = (),
               body_force: tuple[float, float] = (0.0, 0.0), resolution: int = 0,
               threads: int = 0) -> dict[str, object]:
    """`limsurf elasticity --json`'s numbers with the displacement's control values (and fields when resolution > 0)."""
@overload
def elasticity(V: ArrayLike, F: ArrayLike | list[ArrayLike], *, E: float = 1.0, nu: float = 0.3,
               plane_stress: bool = False, boundary: Literal["periodic", "affine", "loaded"] = "periodic",
               macro_deformation: ArrayLike | None = None, face_material: ArrayLike | None = None,
               materials: list[tuple[float, float]] | None = None, levels: int = 0, quadrature: int = 6,
               effective_stiffness: bool = True, crease_interfaces: bool = False,
               clamp: tuple[RectangleSide, ...] | list[RectangleSide] = (),
               tractions: list[tuple[RectangleSide, tuple[float, float]]] | tuple[()] = (),
               body_force: tuple[float, float] = (0.0, 0.0), resolution: int = 0,
               threads: int = 0) -> dict[str, object]: ...

# Reverse Catmull–Clark (docs/guide/reverse.md).
class ReverseLevel(TypedDict):
    fine_vertices: int
    fine_faces: int
    coarse_vertices: int
    coarse_faces: int
    residual_max: float
    residual_rms: float
    unique: bool
    fine_vertex: list[int]

class ReverseInfo(TypedDict):
    method: Literal["least-squares"]
    levels_reversed: int
    per_level: list[ReverseLevel]

def reverse_catmull_clark(mesh: Mesh, levels: int = -1, *, tolerance: float = 1e-9, boundary: Boundary | None = None,
                          creasing: Creasing | None = None,
                          triangles: Triangles | None = None) -> tuple[Mesh, ReverseInfo]:
    """The coarse control mesh that Catmull–Clark refines to `mesh` (`limsurf reverse --json`'s numbers)."""
