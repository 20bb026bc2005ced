"""Pictures and glTF from Python: the same pixels and bytes as `limsurf render`, tessellations on the
limit surface, .glb files checked by an independent reader (glb_reader.py) against the specification."""
import pathlib
import sys

import matplotlib.image
import numpy as np
import pytest

import limsurf

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from glb_reader import read_glb  # noqa: E402  (an independent reader: shares no code with limsurf)


def srgb_to_linear(c):
    c = np.asarray(c, dtype=float)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


@pytest.mark.parametrize("field, extra", [("mean-curvature", []), (None, ["--control-mesh"]),
                                          ("gaussian-curvature", ["--view", "front", "--isolines", "5"])])
def test_render_gives_the_clis_pixels(mesh_path, tmp_path, cli, field, extra):
    png = tmp_path / "cli.png"
    args = ["render", mesh_path("genus2"), "--scheme", "catmull-clark", "--size", "200x150", "--resolution", "6",
            "-o", png, "--json", *extra] + (["--field", field] if field else [])
    theirs = cli(*args)
    ours = limsurf.render(limsurf.read_mesh(mesh_path("genus2")), "catmull-clark", field, size=(200, 150),
                          resolution=6, control_mesh="--control-mesh" in extra, isolines=5 if field and extra else 0,
                          view="front" if extra and field else "iso")
    image = ours["image"]
    assert image.shape == (150, 200, 3) and image.dtype == np.uint8
    decoded = np.rint(matplotlib.image.imread(png)[:, :, :3] * 255).astype(np.uint8)  # an independent PNG reader
    assert np.array_equal(image, decoded)
    assert ours["coverage"] == theirs["coverage"]
    assert ours["field_min"] == theirs["field_min"] and ours["field_max"] == theirs["field_max"]


def test_a_control_field_colours_the_picture_and_the_background_stays(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("sphere_quads"))
    plain = limsurf.render(mesh, "catmull-clark", size=(120, 90), resolution=4)["image"]
    height = limsurf.render(mesh, "catmull-clark", mesh.V[:, 2], size=(120, 90), resolution=4, view="front")
    assert np.array_equal(plain[0, 0], [255, 255, 255]) and np.array_equal(height["image"][0, 0], [255, 255, 255])
    assert height["range"][0] < 0 < height["range"][1]
    # seen from the front, z grows upwards: the top of the sphere is brighter in viridis than its bottom
    column = height["image"][:, 50].astype(int).sum(axis=1)
    rows = np.nonzero(column < 3 * 250)[0]
    assert column[rows[len(rows) // 4]] > column[rows[3 * len(rows) // 4]]


def test_threads_do_not_change_the_picture(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    one, two = (limsurf.render(mesh, "catmull-clark", "mean-curvature", size=(160, 120), resolution=4,
                               threads=threads)["image"] for threads in (1, 2))
    assert np.array_equal(one, two)
    with pytest.raises(limsurf.InputError, match="threads"):
        limsurf.render(mesh, "catmull-clark", threads=-1)


def test_tessellation_lies_on_the_limit_surface(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("cube_creases"))
    t = limsurf.tessellate(mesh, "catmull-clark", resolution=4)
    assert t["triangles"].dtype == np.int32 and t["triangles"].max() < len(t["positions"])
    assert np.allclose(t["value_weights"] @ mesh.V, t["positions"], rtol=0, atol=1e-13)
    basis = limsurf.LimitBasis(mesh, "catmull-clark")
    limit = basis.evaluate(t["faces"], t["u"], t["v"], order=0)
    assert np.allclose(limit["position"], t["positions"], rtol=0, atol=1e-13)
    assert np.allclose(np.linalg.norm(t["normals"], axis=1), 1.0)
    assert np.all(np.isfinite(t["mean_curvature"]))


def test_glb_from_render_matches_the_cli_and_the_specification(mesh_path, tmp_path, cli_tool):
    ours_path, theirs_path = tmp_path / "py.glb", tmp_path / "cli.glb"
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    result = limsurf.render(mesh, "catmull-clark", "mean-curvature", resolution=4, output=ours_path)
    assert "image" not in result
    cli_tool("render", mesh_path("genus2"), "--scheme", "catmull-clark", "--field", "mean-curvature",
             "--resolution", "4", "-o", theirs_path)
    assert ours_path.read_bytes() == theirs_path.read_bytes()
    glb = read_glb(ours_path)
    t = limsurf.tessellate(mesh, "catmull-clark", resolution=4)
    assert np.array_equal(glb.positions, t["positions"].astype(np.float32))
    assert np.array_equal(glb.triangles.astype(np.int64), t["triangles"].astype(np.int64))
    assert np.allclose(glb.normals, t["normals"], atol=1e-6)
    curvature = glb.attributes["_MEAN_CURVATURE"]
    assert np.array_equal(curvature, t["mean_curvature"].astype(np.float32))
    assert glb.colors is not None and glb.colors.shape[0] == len(t["positions"])


def test_write_glb_from_arrays(tmp_path):
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    T = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
    colours = np.array([[1.0, 0.5, 0.0], [0.0, 0.0, 1.0], [0.2, 0.8, 0.2], [0.5, 0.5, 0.5]])
    path = tmp_path / "tetra.glb"
    limsurf.write_glb(path, V, T, colors=colours, scalar=[0.0, 1.0, 2.0, 3.0], scalar_name="height")
    glb = read_glb(path)
    assert np.array_equal(glb.positions, V.astype(np.float32))
    assert np.array_equal(glb.triangles.astype(np.int64), T)
    assert np.allclose(glb.colors[:, :3], srgb_to_linear(colours), atol=1e-6)  # sRGB in, linear COLOR_0 out
    assert np.array_equal(glb.attributes["_HEIGHT"], np.float32([0, 1, 2, 3]))
    with pytest.raises(limsurf.InputError, match=r"triangles\[1, 2\] = 4: vertex index out of range"):
        limsurf.write_glb(tmp_path / "bad.glb", V, np.array([[0, 2, 1], [0, 1, 4]]))
    assert not (tmp_path / "bad.glb").exists()
    with pytest.raises(limsurf.InputError, match="size"):
        limsurf.render(limsurf.Mesh(V, T), "loop", size=(8, 8))
