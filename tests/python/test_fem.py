"""The Galerkin layer: limsurf.plate and limsurf.shell equal `limsurf plate` and `limsurf shell` (their
--json numbers and the arrays of their -o files, bit for bit), the matrices' exact identities, and
bad input."""
import re

import numpy as np
import pytest
import scipy.sparse.linalg

import limsurf

SCORDELIS = dict(E=4.32e8, nu=0.0, thickness=0.25, gravity=90.0)
SCORDELIS_PROBE = (16.06969024216348, 0.0, 19.15111107797445)


def vtu_arrays(path):
    """The named Float64 point arrays of a .vtu file the CLI wrote (shortest round-trip decimals), and
    its points."""
    text = open(path, encoding="utf-8").read()
    out = {}
    for name, comps, body in re.findall(r'<DataArray type="Float64"(?: Name="(\w+)")? NumberOfComponents="(\d)"'
                                        r' format="ascii">(.*?)</DataArray>', text, flags=re.S):
        values = np.array([float(x) for x in body.split()])
        out[name or "Points"] = values.reshape(-1, int(comps)) if comps != "1" else values
    return out


def without_arrays(value):
    """A result as the CLI's JSON has it: no arrays or meshes, tuples as lists."""
    if isinstance(value, dict):
        return {k: without_arrays(v) for k, v in value.items() if not isinstance(v, (np.ndarray, limsurf.Mesh))}
    if isinstance(value, (list, tuple)):
        return [without_arrays(v) for v in value]
    return value


def assert_same_levels(ours, theirs):
    assert len(ours["levels"]) == len(theirs["levels"])
    for mine, cli_level in zip(ours["levels"], theirs["levels"]):
        assert without_arrays(mine) == cli_level


@pytest.mark.parametrize("name, python_load, cli_load, options", [
    ("quad_grid", "uniform", ["--load", "uniform"], dict(levels=2)),
    ("quad_grid", "sinusoidal", ["--load", "sinusoidal", "--pressure", 3], dict(pressure=3.0, levels=1)),
    ("plate_asym", 1e3, ["--load", "uniform", "--pressure", 1e3], dict(support="clamped", E=1e9, nu=0.25,
                                                                       thickness=0.02, degree=8)),
    ("plate_asym", "single-wave", ["--load", "single-wave"], dict(levels=1, tiles=6)),
    # a polynomial: numpy and the CLI's formula parser compute bit-identical values
    ("plate_ev35", lambda P: 1000 * P[:, 0] * P[:, 1], ["--load", "1000*x*y"], dict(levels=1)),
    ("tri_grid", "uniform", ["--load", "uniform", "--scheme", "loop"], dict(levels=1, scheme="loop")),
])
def test_plate_equals_the_cli(mesh_path, cli, tmp_path, name, python_load, cli_load, options):
    flags = {"support": "--support", "E": "--E", "nu": "--nu", "thickness": "--thickness", "degree": "--degree",
             "levels": "--levels"}
    args = [a for k, v in options.items() if k in flags for a in (flags[k], v)]
    out = tmp_path / "plate.vtu"
    theirs = cli("plate", mesh_path(name), *cli_load, *args, "--json", "-o", out)
    options = dict(options)
    scheme = options.pop("scheme", "catmull-clark")
    ours = limsurf.plate(limsurf.read_mesh(mesh_path(name)), scheme, python_load, **options)
    for key in ("scheme", "support", "E", "nu", "thickness", "bending_rigidity", "rectangle"):
        assert ours[key] == theirs[key], key
    assert ours.get("navier") == theirs.get("navier")
    if not callable(python_load):
        assert (ours["load"], ours["pressure"]) == (theirs["load"], theirs["pressure"])
    assert_same_levels(ours, theirs)
    finest = vtu_arrays(out)
    assert np.array_equal(ours["w"], finest["w"])
    assert np.array_equal(ours["mesh"].V, finest["Points"])
    assert ours["levels"][-1]["mesh"].num_faces == theirs["levels"][-1]["faces"]


def test_rectangle_plate_deflection_is_the_clis_reference_and_timoshenkos_table(mesh_path, cli):
    theirs = cli("plate", mesh_path("plate_sym"), "--json")
    box = theirs["rectangle"]
    a, b = box["a"], box["b"]
    D, p = theirs["bending_rigidity"], theirs["pressure"]
    navier = theirs["levels"][0]["navier"]
    assert limsurf.rectangle_plate_deflection(a, b, a / 2, b / 2, D=D, p=p, tolerance=1e-12) == \
        navier["centre_deflection"]
    assert limsurf.rectangle_plate_deflection(a, b, a / 4, b / 4, D=D, p=p, tolerance=1e-12) == \
        navier["quarter_deflection"]
    # Timoshenko & Woinowsky-Krieger, Table 8 (b/a = 2): 0.01013 p a⁴ / D; Navier's series agrees.
    assert abs(limsurf.rectangle_plate_deflection(1.0, 2.0, 0.5, 1.0) - 0.01013) < 5e-6
    x, y = np.meshgrid(np.linspace(0, 1, 5), np.linspace(0, 2, 4))
    levy = limsurf.rectangle_plate_deflection(1.0, 2.0, x, y)
    assert levy.shape == (4, 5) and levy.dtype == np.float64
    assert np.allclose(levy, limsurf.rectangle_plate_deflection(1.0, 2.0, x, y, series="navier", tolerance=1e-12),
                       rtol=0, atol=1e-12)
    wave = limsurf.rectangle_plate_deflection(1.0, 1.0, 0.5, 0.5, waves=(1, 1))
    assert np.isclose(wave, 1 / (4 * np.pi ** 4), rtol=1e-15, atol=0)
    for bad, match in [(dict(a=0.0), "sides"), (dict(D=-1.0), "D must"), (dict(tolerance=0.0), "tolerance"),
                       (dict(x=[0.1, np.nan], y=[0.1, 0.2]), "x"), (dict(x=[0.1, 0.2], y=[0.1]), "same shape"),
                       (dict(series="ritz"), "series"), (dict(waves=(0, 1)), "wave numbers")]:
        args = dict(a=1.0, b=1.0, x=0.5, y=0.5) | bad
        with pytest.raises(limsurf.InputError, match=match):
            limsurf.rectangle_plate_deflection(args.pop("a"), args.pop("b"), args.pop("x"), args.pop("y"), **args)


def test_plate_load_values_equal_the_load_file(mesh_path, cli, tmp_path):
    mesh = limsurf.read_mesh(mesh_path("plate_asym"))
    p = 1e3 * (1.0 + mesh.V[:, 0] * mesh.V[:, 1] / 7.0)
    load_file = tmp_path / "p.txt"
    load_file.write_text("".join(f"{x!r}\n" for x in p))
    out = tmp_path / "plate.vtu"
    theirs = cli("plate", mesh_path("plate_asym"), "--load-file", load_file, "--levels", 1, "--json", "-o", out)
    ours = limsurf.plate(mesh, "catmull-clark", p, levels=1)
    assert ours["load"] == "values" and ours["pressure"] is None and "navier" not in ours["levels"][0]
    assert_same_levels(ours, theirs)
    finest = vtu_arrays(out)
    assert np.array_equal(ours["w"], finest["w"]) and np.array_equal(ours["levels"][1]["p"], finest["p"])
    assert np.array_equal(ours["levels"][0]["p"], p)


def test_shell_equals_the_cli(mesh_path, cli, tmp_path):
    # The Scordelis–Lo roof of docs/guide/shell.md at levels 0–1, the exact cylinder as a Python function.
    out = tmp_path / "roof.vtu"
    theirs = cli("shell", mesh_path("shell_scordelis_lo"), "--E", 4.32e8, "--nu", 0, "--thickness", 0.25,
                 "--gravity", 90, "--fix", "abs(y) > 24.999:xz", "--probe", ",".join(map(repr, SCORDELIS_PROBE)),
                 "--surface", "x^2+z^2-625", "--levels", 1, "--json", "-o", out)
    mesh = limsurf.read_mesh(mesh_path("shell_scordelis_lo"))
    ours = limsurf.shell(mesh, "catmull-clark", **SCORDELIS, supports=[(lambda P: np.abs(P[:, 1]) > 24.999, "xz")],
                         probes=[SCORDELIS_PROBE], surface=lambda P: P[:, 0] ** 2 + P[:, 2] ** 2 - 625, levels=1)
    for key in ("scheme", "E", "nu", "thickness", "interpolate", "solver"):
        assert ours[key] == theirs[key], key
    assert ours["surface"] == "function" and theirs["surface"] == "x^2+z^2-625"
    assert_same_levels(ours, theirs)
    finest = ours["levels"][-1]
    assert ours["u"].shape == (finest["vertices"], 3) and finest["u"] is ours["u"]
    written = vtu_arrays(out)
    assert np.array_equal(finest["limit_displacements"], written["displacement"])
    assert np.array_equal(finest["limit_positions"], written["Points"])
    probe = finest["probes"][0]
    assert np.allclose(finest["limit_displacements"][probe["vertex"]], probe["displacement"], rtol=1e-13, atol=1e-16)
    assert abs(probe["displacement"][2] + 0.298) < 1e-3   # docs/guide/shell.md: u_z = −0.29800 at level 1


def test_shell_point_loads_equal_the_cli(mesh_path, cli):
    # The pinched hemisphere (free edges: all six rigid motions removed), the surface interpolating the given points, level 0.
    loads = [((10, 0, 0), (2, 0, 0)), ((-10, 0, 0), (-2, 0, 0)), ((0, 10, 0), (0, -2, 0)), ((0, -10, 0), (0, 2, 0))]
    theirs = cli("shell", mesh_path("shell_hemisphere"), "--E", 6.825e7, "--nu", 0.3, "--thickness", 0.04,
                 *[a for x, f in loads for a in ("--point-load", f"{','.join(map(str, x))}:{','.join(map(str, f))}")],
                 "--probe", "10,0,0", "--interpolate", "--json")
    ours = limsurf.shell(limsurf.read_mesh(mesh_path("shell_hemisphere")), "catmull-clark", E=6.825e7, nu=0.3,
                         thickness=0.04, point_loads=loads, probes=np.array([[10.0, 0, 0]]), interpolate=True)
    assert ours["interpolate"] and ours["surface"] is None
    assert_same_levels(ours, theirs)
    assert ours["levels"][0]["rigid_motions_removed"] == 6


def test_shell_supports_by_vertex_equal_those_by_position(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("shell_scordelis_lo"))
    ends = [v for loop in mesh.boundary_loops for v in loop if abs(mesh.V[v, 1]) > 24.999]
    by_position = limsurf.shell(mesh, "catmull-clark", **SCORDELIS, supports=[(lambda P: np.abs(P[:, 1]) > 24.999, "xz")])
    by_vertex = limsurf.shell(mesh, "catmull-clark", **SCORDELIS, supports=[(np.array(ends), "xz")])
    assert without_arrays(by_vertex) == without_arrays(by_position)
    assert np.array_equal(by_vertex["u"], by_position["u"])
    with pytest.raises(limsurf.InputError, match="levels = 0"):
        limsurf.shell(mesh, "catmull-clark", **SCORDELIS, supports=[(ends, "xz")], levels=1)
    interior = next(v for v in range(mesh.num_vertices) if all(v not in loop for loop in mesh.boundary_loops))
    with pytest.raises(limsurf.InputError, match=f"vertex {interior} is not a boundary vertex"):
        limsurf.shell(mesh, "catmull-clark", **SCORDELIS, supports=[([interior], "z")])


def test_galerkin_matrices(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    g = limsurf.laplace_beltrami(mesh, "catmull-clark", degree=6, tiles=4)
    M, K = g["mass"], g["stiffness"]
    ones = np.ones(mesh.num_vertices)
    assert abs(M - M.T).max() == 0 and abs(K - K.T).max() < 1e-14 * abs(K).max()
    assert np.abs(K @ ones).max() < 1e-12 * abs(K).max()
    b = limsurf.galerkin_load(mesh, "catmull-clark", lambda P: np.ones(len(P)), degree=6, tiles=4)
    assert np.allclose(b, M @ ones, rtol=1e-12, atol=0)       # the φ_i sum to one
    area = limsurf.measure(mesh, "catmull-clark", degree=6, tiles=4)["area"]
    assert abs(ones @ M @ ones - area) < 1e-10 * area


def test_plate_bending_matrix(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("plate_asym"))
    K = limsurf.plate_bending_matrix(mesh, "catmull-clark")
    assert K.shape == (mesh.num_vertices, mesh.num_vertices) and abs(K - K.T).max() < 1e-14 * abs(K).max()
    x, y = mesh.V[:, 0], mesh.V[:, 1]
    for w in (np.ones_like(x), x, y, 2.0 - 3.0 * x + 0.5 * y):   # affine deflections bend nothing
        assert np.abs(K @ w).max() < 1e-10 * abs(K).max() * np.abs(w).max()
    assert (K @ (x * x)) @ (x * x) > 0
    # plate() is this stiffness with the boundary values fixed and the load of galerkin_load
    boundary = np.unique(np.concatenate(mesh.boundary_loops))
    free = np.setdiff1d(np.arange(mesh.num_vertices), boundary)
    b = limsurf.galerkin_load(mesh, "catmull-clark", lambda P: np.full(len(P), 1e4), degree=6, tiles=6)
    w = np.zeros(mesh.num_vertices)
    w[free] = scipy.sparse.linalg.spsolve(K[free][:, free].tocsc(), b[free])
    assert np.allclose(limsurf.plate(mesh, "catmull-clark", 1e4)["w"], w, rtol=0, atol=1e-10 * np.abs(w).max())


def test_shell_stiffness_and_rigid_body_modes(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("shell_scordelis_lo"))
    K = limsurf.shell_stiffness(mesh, "catmull-clark", E=4.32e8, nu=0.0, thickness=0.25)
    n = 3 * mesh.num_vertices
    assert K.shape == (n, n) and abs(K - K.T).max() < 1e-14 * abs(K).max()
    R = limsurf.rigid_body_modes(mesh)
    assert R.shape == (n, 6) and np.array_equal(R, limsurf.rigid_body_modes(mesh.V))
    assert np.abs(K @ R).max() < 1e-10 * abs(K).max() * np.abs(R).max()
    parts = [limsurf.shell_stiffness(mesh, "catmull-clark", E=4.32e8, nu=0.0, thickness=0.25, terms=t)
             for t in ("membrane", "bending")]
    assert abs(parts[0] + parts[1] - K).max() < 1e-12 * abs(K).max()
    assert np.linalg.matrix_rank(R) == 6


def test_bad_input(mesh_path):
    plate_mesh = limsurf.read_mesh(mesh_path("plate_asym"))
    n = plate_mesh.num_vertices
    with pytest.raises(limsurf.InputError, match=rf"^load: expected {n} values, got 3"):
        limsurf.plate(plate_mesh, "catmull-clark", [1.0, 2.0, 3.0])
    with pytest.raises(limsurf.InputError, match=r"^load\(P\) result: expected"):
        limsurf.plate(plate_mesh, "catmull-clark", lambda P: np.ones(3))
    with pytest.raises(ZeroDivisionError):      # a Python error in a callback propagates as itself
        limsurf.plate(plate_mesh, "catmull-clark", lambda P: 1 / 0)
    with pytest.raises(limsurf.InputError, match="unknown load 'gravity'"):
        limsurf.plate(plate_mesh, "catmull-clark", "gravity")
    with pytest.raises(limsurf.InputError, match="^pressure: "):
        limsurf.plate(plate_mesh, "catmull-clark", 5.0, pressure=3.0)
    with pytest.raises(limsurf.InputError, match="nu must be in"):
        limsurf.plate(plate_mesh, "catmull-clark", 1.0, nu=0.5)
    with pytest.raises(limsurf.InputError, match="unknown plate support 'glued'"):
        limsurf.plate(plate_mesh, "catmull-clark", 1.0, support="glued")
    with pytest.raises(limsurf.InputError, match="needs a boundary"):
        limsurf.plate(limsurf.read_mesh(mesh_path("cube")), "catmull-clark", 1.0)
    with pytest.raises(limsurf.InputError, match="catmull-clark or loop"):
        limsurf.plate(plate_mesh, "doo-sabin", 1.0)
    roof = limsurf.read_mesh(mesh_path("shell_scordelis_lo"))
    with pytest.raises(limsurf.InputError, match="no load"):
        limsurf.shell(roof, "catmull-clark", supports=[(True, "xyz")])
    with pytest.raises(limsurf.InputError, match="letters among x, y, z"):
        limsurf.shell(roof, "catmull-clark", gravity=1.0, supports=[(True, "xq")])
    with pytest.raises(limsurf.InputError, match="no control vertex has its limit point at the probe"):
        limsurf.shell(roof, "catmull-clark", gravity=1.0, supports=[(True, "xyz")], probes=[(1, 2, 3)])
    with pytest.raises(limsurf.InputError, match="support 1 selects no boundary control vertex"):
        limsurf.shell(roof, "catmull-clark", gravity=1.0, supports=[(lambda P: P[:, 1] > 99, "xz")])
    with pytest.raises(KeyError):
        limsurf.shell(roof, "catmull-clark", gravity=1.0, supports=[(lambda P: {}["x"], "xz")])
    with pytest.raises(ZeroDivisionError):
        limsurf.shell(roof, "catmull-clark", gravity=1.0, supports=[(True, "xyz")], surface=lambda P: 1 / 0)
    with pytest.raises(limsurf.InputError, match=r"traction\(P, N\) result"):
        limsurf.shell(roof, "catmull-clark", supports=[(True, "xyz")], traction=lambda P, N: N[:3])
    with pytest.raises(limsurf.InputError, match="terms: unknown"):
        limsurf.shell_stiffness(roof, "catmull-clark", terms="shear")
    with pytest.raises(limsurf.InputError, match=r"^V: expected shape \(n, 3\)"):
        limsurf.rigid_body_modes(np.zeros((4, 2)))


def test_loop_plate(mesh_path):
    # Loop's limit surface is C¹ too: the plate on a triangulated disk sags like the quad disk's.
    tris = limsurf.plate(limsurf.read_mesh(mesh_path("disk_ev7_tris")), "loop", 1e3)
    quads = limsurf.plate(limsurf.read_mesh(mesh_path("disk_ev5_quads")), "catmull-clark", 1e3)
    level = tris["levels"][0]
    assert level["residual"] < 1e-10 and level["max_deflection"] > 0 and tris["load"] == "uniform"
    assert tris["w"].shape == (tris["mesh"].num_vertices,) and np.all(tris["w"] >= -1e-12 * level["max_deflection"])
    assert 0.5 < level["max_deflection"] / quads["levels"][0]["max_deflection"] < 2
