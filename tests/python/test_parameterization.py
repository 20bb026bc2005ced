"""limsurf.parameterize equal to `limsurf parameterize --json`, and its witnesses from Python: a planar
mesh maps onto itself (distortion 1), the circle boundary's limit lies on the unit circle, bad input."""
import numpy as np
import pytest

import limsurf

KEYS = ("method", "level", "boundary", "vertices", "boundary_vertices", "boundary_loops", "solver", "eigenvalue",
        "iterations", "residual", "boundary_length", "u_min", "u_max", "v_min", "v_max", "distortion")


@pytest.mark.parametrize("name, scheme, method, boundary", [("shell_hemisphere", "catmull-clark", "sec", "free"),
                                                            ("disk_ev7_tris", "loop", "dec", "free"),
                                                            ("disk_ev5_quads", "catmull-clark", "secsnap", "circle"),
                                                            ("disk_ev7_tris", "loop", "iga", "free")])
def test_parameterize_equals_the_cli(mesh_path, cli, name, scheme, method, boundary):
    extra = ("--reference-level", 2) if boundary == "circle" else ()
    level = 2 if method.startswith("sec") else None  # both sides refuse a level with dec and iga
    theirs = cli("parameterize", mesh_path(name), "--scheme", scheme, "--method", method,
                 *(("--level", level) if level else ()), "--boundary", boundary, *extra, "--json")
    ours = limsurf.parameterize(limsurf.read_mesh(mesh_path(name)), scheme, method=method, level=level,
                                boundary=boundary, reference_level=2 if boundary == "circle" else None)
    for key in KEYS:
        assert ours[key] == theirs[key], key
    assert ours.get("reference") == theirs.get("reference")
    assert ours["uv"].shape == (ours["vertices"], 2) and ours["uv"][:, 0].min() == theirs["u_min"]


def test_planar_mesh_maps_onto_itself(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("quad_grid"))
    r = limsurf.parameterize(mesh, "catmull-clark", method="sec", level=2)
    uv = r["uv"]
    # uv = R (x, y) + t with R a rotation: all pairwise distances are kept.
    xy = mesh.V[:, :2]
    d_xy = np.linalg.norm(xy[:, None, :] - xy[None, :, :], axis=2)
    d_uv = np.linalg.norm(uv[:, None, :] - uv[None, :, :], axis=2)
    assert np.abs(d_xy - d_uv).max() < 1e-9   # measured 1.3e-10 on distances up to 2.8
    assert abs(r["distortion"]["mean"] - 1) < 1e-8 and r["distortion"]["flipped"] == 0


def test_circle_boundary_and_errors(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("disk_ev5_quads"))
    r = limsurf.parameterize(mesh, "catmull-clark", method="dec", boundary="circle")
    uv = r["uv"]
    (loop,) = mesh.boundary_loops
    # The limit point of a Catmull–Clark boundary vertex is (1, 4, 1)/6 of it and its boundary
    # neighbours, except at a corner (a vertex of one face: the boundary rule keeps it in place);
    # those limit points lie on the unit circle, in loop order, counter-clockwise.
    faces_at = np.bincount(mesh.face_vertices, minlength=mesh.num_vertices)
    limit = (np.roll(uv[loop], 1, axis=0) + 4 * uv[loop] + np.roll(uv[loop], -1, axis=0)) / 6
    corner = faces_at[loop] == 1
    assert corner.sum() == 5   # the pentagon's corners
    limit[corner] = uv[loop][corner]
    assert np.abs(np.linalg.norm(limit, axis=1) - 1).max() < 1e-12
    angles = np.unwrap(np.arctan2(limit[:, 1], limit[:, 0]))
    assert np.all(np.diff(angles) > 0) and abs(angles[-1] - angles[0] - 2 * np.pi * (1 - 1 / len(loop))) < 0.2
    # Harmonic interior: inside the disk (maximum principle).
    interior = np.setdiff1d(np.arange(mesh.num_vertices), loop)
    assert np.linalg.norm(uv[interior], axis=1).max() < 1
    with pytest.raises(limsurf.InputError, match="closed"):
        limsurf.parameterize(limsurf.read_mesh(mesh_path("sphere_quads")), "catmull-clark")
    with pytest.raises(limsurf.InputError, match="2 boundary loops"):
        limsurf.parameterize(limsurf.read_mesh(mesh_path("annulus")), "catmull-clark", boundary="circle")
    with pytest.raises(limsurf.InputError, match="expected free or circle"):
        limsurf.parameterize(mesh, "catmull-clark", boundary="square")
