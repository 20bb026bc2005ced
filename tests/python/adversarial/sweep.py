#!/usr/bin/env python3
"""Calls every public function and method of the limsurf module with hostile arguments, one at a
time, and checks the module's promise for bad input (issue 15): a call returns a finite result or
raises limsurf.Error (InputError, TopologyError, NumericalError, UnsupportedError) or TypeError —
never a crash, a hang, another exception type, or nan/inf in a result that does not document it.

Each function starts from a known-good call (BASELINES); each parameter in turn, positional or
keyword, is replaced by the hostile values of its annotation (read from the docstring's signature:
floats at the edges of a double, ints at the edges of int32/int64, odd strings, arrays that are
empty, nan, ragged, of the wrong rank or dtype, meshes scaled to 1e-300 and 1e300 or collapsed to
a point). Every call runs in its own interpreter with a time limit, so a crash or a hang is caught
and named. The last line is "N calls: M flagged".

Usage: PYTHONPATH=build/ci/python sweep.py MESH_DIR [--only NAME...] [--jobs N] [--timeout S] [--meshes DIR]

With --meshes DIR every mesh of DIR (.obj, .off, .ply; e.g. tests/data/opensubdiv_shapes) is given,
in turn, to every parameter annotated as a Mesh, instead of the hostile values above: each call must
then return a finite result or refuse by a limsurf.Error.
Run by hand (a few minutes on 2 cores), not by the suite; tests/python/test_hostile_inputs.py keeps
what earlier sweeps found.
"""
import argparse
import concurrent.futures
import json
import math
import os
import pathlib
import subprocess
import sys
import tempfile

# Result keys whose nan or inf the docstrings promise (curvature where it is undefined, R without
# a saddle part or a shape), and results that are not numbers.
DOCUMENTED_NON_FINITE = {"mean_curvature", "gaussian_curvature", "k1", "k2", "ratio"}

FLOATS = [math.nan, math.inf, -math.inf, -1.0, 0.0, 5e-324, 1e308, -1e308]
INTS = [-1, 0, 2**31, -(2**31) - 1, 2**63 - 1, -(2**63)]
STRINGS = ["", "bogus", "x" * 10000, "\u00e9\u0000"]


def hostile_arrays():
    import numpy as np
    return {
        "[]": [],
        "empty (0, 3)": np.empty((0, 3)),
        "nan (3, 3)": np.full((3, 3), np.nan),
        "1e308 (4, 3)": np.full((4, 3), 1e308),
        "rank 3": np.zeros((2, 2, 2)),
        "ragged": [[0, 1], [2]],
        "str": "abc",
        "dict": {"a": 1},
        "object array": np.array([None, 1], dtype=object),
        "int64 max": np.array([2**63 - 1]),
        "-1": np.array([-1]),
        "bool": np.array([True, False]),
        "complex": np.ones(3, dtype=complex),
    }


def meshes(mesh_dir):
    import limsurf
    read = lambda name: limsurf.read_mesh(str(pathlib.Path(mesh_dir) / (name + ".obj")))
    return {name: read(name) for name in ("cube", "icosahedron", "quad_torus", "quad_grid", "tri_grid",
                                          "plate_ev35", "disk_ev5_quads", "rve_block", "tetra_1",
                                          "shell_scordelis_lo")}


def hostile_meshes(mesh):
    import limsurf
    out = {}
    for name, factor in (("scaled 1e-300", 1e-300), ("scaled 1e300", 1e300), ("collapsed", 0.0)):
        try:
            out[name] = mesh.with_positions(mesh.V * factor)
        except limsurf.Error:
            pass
    return out


def baselines(mesh_dir, tmp):
    """{name: (callable, args, kwargs)}: a good call of every public function and method."""
    import numpy as np
    import limsurf
    m = meshes(mesh_dir)
    cube, ico = m["cube"], m["icosahedron"]
    basis = limsurf.LimitBasis(cube, "catmull-clark")
    heat = limsurf.HeatGeodesics(cube, "catmull-clark", method="dec")
    tess = limsurf.tessellate(cube, "catmull-clark", resolution=2)
    rhs = cube.V[:, 0] - cube.V[:, 0].mean()
    roof_ends = lambda P: np.abs(P[:, 1]) > 24.999
    out = {
        "info": (limsurf.info, (cube,), {}),
        "submesh": (limsurf.submesh, (cube, [True, False, True, True, False, True]), {}),
        "volume": (limsurf.volume, (cube, "catmull-clark"), {}),
        "measure": (limsurf.measure, (cube, "catmull-clark"), {"degree": 4, "tiles": 2}),
        "subdivide": (limsurf.subdivide, (cube, "catmull-clark", 1), {}),
        "tessellate": (limsurf.tessellate, (cube, "catmull-clark"), {"resolution": 2}),
        "exterior_derivatives": (limsurf.exterior_derivatives, (cube,), {}),
        "inner_products": (limsurf.inner_products, (cube, "catmull-clark"), {"level": 1}),
        "operators": (limsurf.operators, (cube, "catmull-clark"), {"level": 1}),
        "laplace_beltrami": (limsurf.laplace_beltrami, (cube, "catmull-clark"), {"degree": 4, "tiles": 2}),
        "poisson": (limsurf.poisson, (cube, "catmull-clark", rhs), {"level": 1}),
        "geodesic_distance": (limsurf.geodesic_distance, (cube, "catmull-clark", [0]), {"level": 1}),
        "harmonic_basis": (limsurf.harmonic_basis, (m["quad_torus"], "catmull-clark"), {"level": 1}),
        "hodge_decomposition": (limsurf.hodge_decomposition, (m["quad_torus"], "catmull-clark"),
                                {"random": 1, "level": 1}),
        "one_form_vectors": (limsurf.one_form_vectors, (cube, "catmull-clark", np.ones(cube.num_edges)),
                             {"level": 1}),
        "design_vector_field": (limsurf.design_vector_field, (cube, "catmull-clark"),
                                {"sources": [(0, 1.0)], "sinks": [(7, 1.0)], "level": 1}),
        "parameterize": (limsurf.parameterize, (m["disk_ev5_quads"], "catmull-clark"), {"level": 1}),
        "plate": (limsurf.plate, (m["quad_grid"], "catmull-clark", "uniform"), {}),
        "plate_bending_matrix": (limsurf.plate_bending_matrix, (m["quad_grid"], "catmull-clark"), {}),
        "shell_stiffness": (limsurf.shell_stiffness, (cube, "catmull-clark"), {"degree": 3, "tiles": 2}),
        "shell": (limsurf.shell, (m["shell_scordelis_lo"], "catmull-clark"),
                  {"E": 4.32e8, "nu": 0.0, "thickness": 0.25, "gravity": 90.0, "supports": [(roof_ends, "xz")]}),
        "galerkin_load": (limsurf.galerkin_load, (m["quad_grid"], "catmull-clark", lambda P: np.ones(len(P))), {}),
        "rigid_body_modes": (limsurf.rigid_body_modes, (cube.V,), {}),
        "elasticity": (limsurf.elasticity, (m["rve_block"],), {}),
        "shape_functionals": (limsurf.shape_functionals, (ico, "loop"), {}),
        "minimize_membrane": (limsurf.minimize_membrane, (ico, "loop"),
                              {"area": 4 * math.pi, "reduced_volume": 0.9, "max_iterations": 3}),
        "self_intersections": (limsurf.self_intersections, (cube, "catmull-clark"), {}),
        "decompose_shapes": (limsurf.decompose_shapes, (m["plate_ev35"],), {}),
        "one_ring_spectrum": (limsurf.one_ring_spectrum, (5,), {}),
        "quadratic_shape_errors": (limsurf.quadratic_shape_errors, (5,), {"quadrature": 2, "tile_levels": 3}),
        "tune_weights": (limsurf.tune_weights, (5,), {"quadrature": 2, "tile_levels": 3, "samples": 5}),
        "tuned_vertex_weights": (limsurf.tuned_vertex_weights, (5,), {"quadrature": 2, "tile_levels": 3}),
        "weights_for_subdominant": (limsurf.weights_for_subdominant, (5, 0.56), {}),
        "feasible_subdominant_range": (limsurf.feasible_subdominant_range, (5,), {}),
        "reverse_catmull_clark": (limsurf.reverse_catmull_clark, (limsurf.subdivide(cube, "catmull-clark", 1),), {}),
        "render": (limsurf.render, (cube, "catmull-clark"), {"size": (80, 60)}),
        "write_mesh": (limsurf.write_mesh, (os.path.join(tmp, "out.obj"), cube), {}),
        "write_glb": (limsurf.write_glb, (os.path.join(tmp, "out.glb"), tess["positions"], tess["triangles"]), {}),
        "read_mesh": (limsurf.read_mesh, (str(pathlib.Path(mesh_dir) / "cube.obj"),), {}),
        "Mesh": (limsurf.Mesh, (cube.V, cube.F), {}),
        "Mesh.with_positions": (cube.with_positions, (cube.V,), {}),
        "LimitBasis": (limsurf.LimitBasis, (cube, "catmull-clark"), {}),
        "LimitBasis.evaluate": (basis.evaluate, ([0], [0.5], [0.5]), {}),
        "LimitBasis.weights": (basis.weights, ([0], [0.5], [0.5]), {"order": 2}),
        "LimitBasis.ptex_face": (basis.ptex_face, (0,), {}),
        "LimitBasis.limit_positions": (basis.limit_positions, (), {}),
        "HeatGeodesics": (limsurf.HeatGeodesics, (cube, "catmull-clark"), {"method": "dec"}),
        "HeatGeodesics.distance": (heat.distance, ([0],), {}),
        "HeatGeodesics.distances": (heat.distances, ([[0], [1]],), {}),
        "HeatGeodesics.source_values": (heat.source_values, (np.ones(cube.num_vertices), [0]), {}),
    }
    return out, m


def signatures(function):
    """The parameter lists of the overloads of a pybind11 callable (self dropped for methods)."""
    from limsurf import _arguments
    doc = getattr(function, "__wrapped__", function).__doc__
    return [[p for p in parameters if p[0] != "self"]
            for parameters in _arguments.docstring_signatures(doc) if parameters is not None]


def mesh_files(folder):
    return sorted(str(p) for p in pathlib.Path(folder).iterdir() if p.suffix in (".obj", ".off", ".ply"))


def hostile_values(annotation, mesh, meshes_dir=None):
    annotation = annotation.replace("Optional[", "").rstrip("]") if annotation.startswith("Optional[") else annotation
    if meshes_dir and not annotation.endswith("Mesh"):
        return []
    if annotation == "float":
        return [(repr(v), v) for v in FLOATS]
    if annotation == "int":
        return [(repr(v), v) for v in INTS]
    if annotation == "str":
        return [(repr(v[:20]), v) for v in STRINGS]
    if annotation.endswith("Mesh"):
        if meshes_dir:
            return [(pathlib.Path(f).name, f) for f in mesh_files(meshes_dir)]  # read in the child
        return list(hostile_meshes(mesh).items())
    if annotation in ("handle", "object", "Iterable", "sequence") or annotation.startswith(("List[", "Tuple[")):
        return list(hostile_arrays().items())
    return []


def cases(mesh_dir, only, meshes_dir=None):
    """(name, parameter, label) of every call to make."""
    with tempfile.TemporaryDirectory() as tmp:
        table, m = baselines(mesh_dir, tmp)
        out = []
        for name, (function, args, kwargs) in table.items():
            if only and name not in only:
                continue
            for parameters in signatures(function)[:1]:
                mesh = args[0] if args and type(args[0]).__name__ == "Mesh" else m["cube"]
                for parameter, annotation, _, _ in parameters:
                    for label, _ in hostile_values(annotation, mesh, meshes_dir):
                        out.append((name, parameter, label))
        return out


def run_case(mesh_dir, name, parameter, label, meshes_dir=None):
    """In the child: builds the baseline, replaces one argument, calls, and prints a JSON verdict."""
    import numpy as np
    import limsurf
    with tempfile.TemporaryDirectory() as tmp:
        table, m = baselines(mesh_dir, tmp)
        function, args, kwargs = table[name]
        parameters = signatures(function)[0]
        mesh = args[0] if args and type(args[0]).__name__ == "Mesh" else m["cube"]
        annotation = next(a for p, a, _, _ in parameters if p == parameter)
        value = dict(hostile_values(annotation, mesh, meshes_dir))[label]
        if meshes_dir:
            try:
                value = limsurf.read_mesh(value)
            except limsurf.Error as error:
                return {"verdict": "refused", "message": "read_mesh: " + str(error).splitlines()[0][:200]}
        names = [p for p, _, _, keyword_only in parameters if not keyword_only]
        args = list(args)
        kwargs = dict(kwargs)
        if parameter in names and names.index(parameter) < len(args):
            args[names.index(parameter)] = value
        else:
            kwargs[parameter] = value
        try:
            result = function(*args, **kwargs)
        except (limsurf.Error, TypeError) as error:
            return {"verdict": "refused", "message": str(error).splitlines()[0][:200]}
        except BaseException as error:  # noqa: BLE001 - any other type is what the sweep looks for
            return {"verdict": "unexpected exception", "message": f"{type(error).__name__}: {str(error)[:200]}"}
        bad = non_finite(result)
        if bad:
            return {"verdict": "non-finite result", "message": bad}
        return {"verdict": "returned", "message": ""}


def non_finite(value, path=""):
    import numpy as np
    if isinstance(value, dict):
        for key, item in value.items():
            if key in DOCUMENTED_NON_FINITE:
                continue
            found = non_finite(item, f"{path}.{key}")
            if found:
                return found
    elif isinstance(value, (list, tuple)):
        for i, item in enumerate(value):
            found = non_finite(item, f"{path}[{i}]")
            if found:
                return found
    elif isinstance(value, float) and not math.isfinite(value):
        return f"{path} = {value}"
    elif isinstance(value, np.ndarray) and value.dtype.kind == "f" and not np.all(np.isfinite(value)):
        return f"{path} has {int(np.sum(~np.isfinite(value)))} non-finite entries"
    elif hasattr(value, "data") and hasattr(value, "nnz"):  # scipy sparse
        if not np.all(np.isfinite(value.data)):
            return f"{path} (sparse) has non-finite entries"
    return ""


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("mesh_dir")
    parser.add_argument("--only", nargs="*", default=[])
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--timeout", type=float, default=120.0)
    parser.add_argument("--meshes", default=None)
    parser.add_argument("--case", help=argparse.SUPPRESS)  # JSON [name, parameter, label]: labels may start with -
    options = parser.parse_args()
    if options.case:
        print(json.dumps(run_case(options.mesh_dir, *json.loads(options.case), options.meshes)))
        return 0
    with tempfile.TemporaryDirectory() as tmp:  # every baseline must succeed, or its mutations prove nothing
        for name, (function, args, kwargs) in baselines(options.mesh_dir, tmp)[0].items():
            if options.only and name not in options.only:
                continue
            try:
                function(*args, **kwargs)
            except Exception as error:  # noqa: BLE001
                print(f"baseline {name} fails: {type(error).__name__}: {error}")
                return 2
    todo = cases(options.mesh_dir, set(options.only), options.meshes)

    def child(case):
        try:
            meshes = ["--meshes", options.meshes] if options.meshes else []
            done = subprocess.run([sys.executable, __file__, options.mesh_dir, *meshes, "--case=" + json.dumps(case)],
                                  capture_output=True, text=True, timeout=options.timeout)
        except subprocess.TimeoutExpired:
            return case, {"verdict": "hang", "message": f"over {options.timeout} s"}
        if done.returncode != 0:
            return case, {"verdict": "crash", "message": f"exit {done.returncode}: {done.stderr.strip()[-300:]}"}
        lines = done.stdout.strip().splitlines()
        verdict = json.loads(lines[-1]) if lines else {"verdict": "crash", "message": "no output"}
        if len(lines) > 1:
            verdict["printed"] = "\n".join(lines[:-1])[:200]  # the library must not print
        return case, verdict

    flagged = 0
    with concurrent.futures.ThreadPoolExecutor(options.jobs) as pool:
        for (name, parameter, label), verdict in pool.map(child, todo):
            bad = verdict["verdict"] in ("hang", "crash", "unexpected exception", "non-finite result") or "printed" in verdict
            flagged += bad
            if bad:
                print(f"FLAG {name}({parameter}={label}): {verdict['verdict']}: {verdict['message']} "
                      f"{verdict.get('printed', '')}", flush=True)
    print(f"{len(todo)} calls: {flagged} flagged")
    return 1 if flagged else 0


if __name__ == "__main__":
    sys.exit(main())
