#!/usr/bin/env python3
"""Mutation fuzzing of the Python module's array arguments (docs/io.md "Fuzzing").

Issue 15 promises that wrong dtypes or shapes, non-contiguous arrays, indices past the end and NaN
positions raise a Python exception that names the array, and never crash the interpreter. This
script calls the module's functions with one array argument changed at a time — another dtype,
shape, memory order or stride, NaN, infinities, huge or negative values, an index past the end,
nested lists, None — and the others right.

A finding is a signal (the interpreter died: the call is named by its seed and iteration), or an
exception other than limsurf's own errors, TypeError, ValueError, IndexError, OverflowError and
MemoryError (a C++ exception that escaped as RuntimeError, say). The calls run in a child process,
restarted after a crash.

    PYTHONPATH=build/ci/python /usr/bin/python3 fuzz/python_api.py --iterations 3000 --seed 1
"""
import argparse
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MESHES = os.path.join(ROOT, "data", "meshes")


def odd_array(rng, good):
    """`good` (an array) changed in one way."""
    import numpy as np
    good = np.asarray(good)
    kind = rng.integers(16)
    if kind == 0:
        return good.astype(rng.choice(["int8", "uint64", "float32", "complex128", "bool", "int32", "float16"]))
    if kind == 1:
        return good.astype(object)
    if kind == 2:
        return good.T if good.ndim > 1 else good[:, None]
    if kind == 3:
        return good[..., None]
    if kind == 4:
        return good[: rng.integers(len(good) + 1)] if good.ndim else good
    if kind == 5:
        return np.repeat(good, 2, axis=0)[::2] if good.ndim else good  # non-contiguous, same values
    if kind == 6:
        return np.asfortranarray(good)
    if kind in (7, 8, 9):
        bad = good.astype(float).copy()
        if bad.size:
            bad.flat[rng.integers(bad.size)] = rng.choice([np.nan, np.inf, -np.inf, 1e308, -1e308, 1e-320])
        return bad
    if kind in (10, 11):
        bad = good.copy()
        if bad.size and np.issubdtype(bad.dtype, np.integer):
            bad.flat[rng.integers(bad.size)] = rng.choice([-1, -2**31, 2**31 - 1, 10**6, good.max() + 1])
        elif bad.size:
            bad.flat[rng.integers(bad.size)] = np.nan
        return bad
    if kind == 12:
        return good.tolist()
    if kind == 13:
        return None
    if kind == 14:
        return np.zeros((0,) + good.shape[1:], dtype=good.dtype)
    return "abc"


def cases(limsurf, np):
    """(name, make(rng) -> call) for every function that takes arrays."""
    cube = limsurf.read_mesh(os.path.join(MESHES, "cube.obj"))
    ico = limsurf.read_mesh(os.path.join(MESHES, "icosahedron.obj"))
    plate = limsurf.read_mesh(os.path.join(MESHES, "plate_sym.obj"))
    cc = limsurf.LimitBasis(cube, "catmull-clark")
    loop = limsurf.LimitBasis(ico, "loop")

    def points(rng, basis, n=7):  # inside the domain: the unit square, or the triangle (halved)
        u, v = rng.random(n), rng.random(n)
        if basis.domain == "triangle":
            u, v = u / 2, v / 2
        return rng.integers(0, basis.num_ptex_faces, n), u, v

    def mutate(rng, args):
        """One of the array arguments in `args` (a dict) changed."""
        name = list(args)[rng.integers(len(args))]
        args = dict(args)
        args[name] = odd_array(rng, args[name])
        return args

    def evaluate(rng):
        basis = cc if rng.random() < 0.5 else loop
        faces, u, v = points(rng, basis)
        a = mutate(rng, {"faces": faces, "u": u, "v": v, "X": basis.mesh.V})
        return lambda: basis.evaluate(a["faces"], a["u"], a["v"], order=int(rng.integers(3)), X=a["X"],
                                      threads=int(rng.integers(3)))

    def evaluate_out(rng):
        faces, u, v = points(rng, cc)
        out = cc.evaluate(faces, u, v, order=2)
        key = list(out)[rng.integers(len(out))]
        out[key] = odd_array(rng, out[key])
        return lambda: cc.evaluate(faces, u, v, order=2, out=out)

    def weights(rng):
        a = mutate(rng, dict(zip(["faces", "u", "v"], points(rng, loop))))
        return lambda: loop.weights(a["faces"], a["u"], a["v"], order=int(rng.integers(3)))

    def patch(rng):
        a = mutate(rng, {"X": cube.V})
        return lambda: cc.patch(int(rng.integers(6)), 0.3, 0.6, X=a["X"], points=bool(rng.integers(2)))

    def mesh(rng):
        base = cube if rng.random() < 0.5 else ico
        a = mutate(rng, {"V": base.V, "F": np.array(base.F)})
        return lambda: limsurf.Mesh(a["V"], a["F"])

    def with_positions(rng):
        a = mutate(rng, {"V": ico.V})
        return lambda: ico.with_positions(a["V"])

    def volume(rng):
        a = mutate(rng, {"X": cube.V})
        return lambda: limsurf.volume(cube, "catmull-clark", gradient=bool(rng.integers(2)), X=a["X"])

    def limit_positions(rng):
        a = mutate(rng, {"X": ico.V})
        return lambda: loop.limit_positions(X=a["X"])

    def poisson(rng):
        a = mutate(rng, {"rhs": np.ones(cube.num_vertices)})
        method = str(rng.choice(["dec", "sec"]))
        return lambda: limsurf.poisson(cube, "catmull-clark", a["rhs"], method=method,
                                       **({"level": 1} if method == "sec" else {}))

    def geodesic(rng):
        a = mutate(rng, {"sources": np.array([0, 3])})
        return lambda: limsurf.geodesic_distance(ico, "loop", a["sources"], method="dec")

    def plate_load(rng):
        a = mutate(rng, {"load": np.ones(plate.num_vertices)})
        return lambda: limsurf.plate(plate, "catmull-clark", a["load"])

    def rectangle_plate(rng):
        x, y = rng.random((2, 3, 4))
        a = mutate(rng, {"x": x, "y": y})
        waves = (1, 2) if rng.random() < 0.3 else None
        return lambda: limsurf.rectangle_plate_deflection(1.0, 2.0, a["x"], a["y"], waves=waves,
                                                          series=str(rng.choice(["levy", "navier"])), tolerance=1e-8)

    def tessellate(rng):
        a = mutate(rng, {"X": ico.V})
        return lambda: limsurf.tessellate(ico, "loop", resolution=2, X=a["X"])

    def one_form(rng):
        a = mutate(rng, {"w": np.ones(ico.num_edges)})
        return lambda: limsurf.one_form_vectors(ico, "loop", a["w"], level=1)

    def hodge(rng):
        a = mutate(rng, {"w": np.ones(cube.num_edges)})
        return lambda: limsurf.hodge_decomposition(cube, "catmull-clark", a["w"], method="dec", basis=False)

    def submesh(rng):
        base = cube if rng.random() < 0.5 else ico
        a = mutate(rng, {"keep": rng.random(base.num_faces) < 0.6})
        return lambda: limsurf.submesh(base, a["keep"])

    def subdivide(rng):  # from arrays, with the operators and only the finest level's faces kept
        base = cube if rng.random() < 0.5 else ico
        a = mutate(rng, {"V": base.V, "F": np.array(base.F)})
        scheme = "catmull-clark" if base is cube else str(rng.choice(["loop", "catmull-clark"]))
        return lambda: limsurf.subdivide(a["V"], a["F"], scheme, int(rng.integers(3)), operators=True,
                                         forms=bool(rng.integers(2)), topology=False)

    shape = limsurf.ShapeEvaluator(ico, "loop", threads=1)

    def shape_evaluate(rng):
        a = mutate(rng, {"X": ico.V})
        return lambda: shape.evaluate(a["X"], gradients=bool(rng.integers(2)))

    def eigen(rng):  # the weights as an odd array, with odd valences and rings
        a = mutate(rng, {"weights": np.array([13.4575, 0.999938, 0.999938])})
        valence = int(rng.choice([-1, 0, 2, 3, 5, 7, 129, 2**31 - 1]))
        scheme = str(rng.choice(["catmull-clark", "loop", "c2g0", "doo-sabin", "bilinear"]))
        return lambda: limsurf.eigen_analysis(scheme, valence, boundary=bool(rng.integers(2)), weights=a["weights"],
                                              rings=int(rng.choice([-1, 0, 1, 3, 9])))

    return [("LimitBasis.evaluate", evaluate), ("LimitBasis.evaluate(out=)", evaluate_out),
            ("LimitBasis.weights", weights), ("LimitBasis.patch", patch), ("Mesh", mesh),
            ("Mesh.with_positions", with_positions), ("volume", volume), ("LimitBasis.limit_positions", limit_positions),
            ("poisson", poisson), ("geodesic_distance", geodesic), ("plate", plate_load),
            ("rectangle_plate_deflection", rectangle_plate), ("tessellate", tessellate),
            ("one_form_vectors", one_form), ("hodge_decomposition", hodge), ("submesh", submesh),
            ("subdivide", subdivide), ("eigen_analysis", eigen), ("ShapeEvaluator.evaluate", shape_evaluate)]


def child(seed, first, last, progress):
    """Iterations first..last-1; each writes its number to `progress` before its call."""
    import warnings

    import numpy as np

    import limsurf
    warnings.simplefilter("ignore")
    expected = (limsurf.Error, TypeError, ValueError, IndexError, OverflowError, MemoryError)
    table = cases(limsurf, np)
    for iteration in range(first, last):
        rng = np.random.default_rng([seed, iteration])
        name, make = table[rng.integers(len(table))]
        with open(progress, "w") as f:
            f.write("%d %s\n" % (iteration, name))
        try:
            make(rng)()
        except expected:
            pass
        except Exception as error:  # noqa: BLE001 - anything else is a finding
            print("finding: iteration %d, %s raised %s: %s" % (iteration, name, type(error).__name__, error),
                  flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--iterations", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--child", nargs=3, type=int, help=argparse.SUPPRESS)
    parser.add_argument("--progress", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        child(*args.child, args.progress)
        return 0
    findings = 0
    progress = tempfile.mktemp(prefix="limsurf-pyfuzz-")
    first = 0
    while first < args.iterations:
        run = subprocess.run([sys.executable, __file__, "--child", str(args.seed), str(first), str(args.iterations),
                              "--progress", progress], capture_output=True, text=True)
        sys.stdout.write(run.stdout)
        findings += run.stdout.count("finding:")
        if run.returncode == 0:
            break
        if not os.path.exists(progress):  # it failed before its first call
            print(run.stderr, file=sys.stderr)
            return 2
        with open(progress) as f:
            where = f.read().strip()
        print("finding: the interpreter died (%d) at iteration %s; stderr: %s" %
              (run.returncode, where, run.stderr.strip()[-500:]), flush=True)
        findings += 1
        first = int(where.split()[0]) + 1
    if os.path.exists(progress):
        os.remove(progress)
    print("%d iterations, %d findings" % (args.iterations, findings))
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
