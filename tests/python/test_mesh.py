"""limsurf.Mesh, read_mesh, write_mesh, info: arrays in and out, files, ownership, bad input."""
import gc
import warnings

import numpy as np
import pytest

import limsurf

CUBE_V = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                   [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
CUBE_F = np.array([[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]])


def test_round_trip_mesh_to_numpy_to_mesh(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    again = limsurf.Mesh(mesh.V, mesh.F)
    assert np.array_equal(again.V, mesh.V)
    assert np.array_equal(again.F, mesh.F)
    assert again.num_edges == mesh.num_edges and again.genus == mesh.genus == 2
    assert np.array_equal(again.edges, mesh.edges)


def test_arrays_have_the_promised_dtypes_and_shapes():
    mesh = limsurf.Mesh(CUBE_V, CUBE_F)
    assert mesh.V.dtype == np.float64 and mesh.V.shape == (8, 3)
    assert mesh.F.dtype == np.int32 and mesh.F.shape == (6, 4)
    assert mesh.edges.shape == (12, 2) and mesh.edges.dtype == np.int32
    assert np.all(mesh.edges[:, 0] < mesh.edges[:, 1])
    assert mesh.face_offsets.tolist() == [0, 4, 8, 12, 16, 20, 24]
    assert mesh.is_closed and mesh.genus == 0 and mesh.num_faces == 6


def test_V_is_a_read_only_view_that_keeps_the_mesh_alive():
    mesh = limsurf.Mesh(CUBE_V, CUBE_F)
    first, second = mesh.V, mesh.V
    assert np.shares_memory(first, second), "V must be a view of the mesh's memory, not a copy"
    assert not first.flags.writeable
    with pytest.raises(ValueError):
        first[0, 0] = 5.0
    del mesh, second
    gc.collect()
    junk = [np.full((8, 3), 7.0) for _ in range(100)]  # reuse freed memory, were the view dangling
    assert np.array_equal(first, CUBE_V), "the view outlived its mesh"
    del junk


def test_input_arrays_are_copied_and_any_layout_is_accepted():
    V = np.asfortranarray(CUBE_V.copy())
    strided = np.zeros((8, 6))
    strided[:, ::2] = CUBE_V
    for variant in (V, strided[:, ::2], CUBE_V.astype(np.float32), CUBE_V.astype(np.int64), CUBE_V.tolist()):
        mesh = limsurf.Mesh(variant, CUBE_F.astype(np.int64))
        assert np.array_equal(mesh.V, CUBE_V)
    source = CUBE_V.copy()
    mesh = limsurf.Mesh(source, CUBE_F)
    source[:] = 0
    assert np.array_equal(mesh.V, CUBE_V), "the mesh must own a copy of V"


def test_polygons_of_mixed_degree_come_as_lists():
    V = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0], [1, 1, 0], [2, 1, 0], [1.5, 2, 0]], float)
    F = [[0, 1, 4, 3], [1, 2, 5, 4], [4, 5, 6]]
    mesh = limsurf.Mesh(V, F)
    assert isinstance(mesh.F, list) and [f.tolist() for f in mesh.F] == F
    assert mesh.face_vertices.tolist() == sum(F, [])
    assert not mesh.is_closed and len(mesh.boundary_loops) == 1


def test_info_matches_the_cli(mesh_path, cli):
    for name in ("genus2", "cube_creases", "quad_grid_boundary" if False else "tetra_2"):
        ours = limsurf.info(limsurf.read_mesh(mesh_path(name)))
        theirs = cli("info", "--json", mesh_path(name))
        for key in ("num_vertices", "num_edges", "num_faces", "num_corners", "euler_characteristic", "genus",
                    "num_components", "num_boundary_loops", "boundary_loop_lengths", "is_closed", "sharpness",
                    "scheme_hints"):
            assert ours[key] == theirs[key], key
        for key in ("face_degree_histogram", "valence_histogram"):
            assert {str(k): v for k, v in ours[key].items()} == theirs[key], key
        assert [list(x) for x in (ours["bounding_box"]["min"], ours["bounding_box"]["max"])] == \
            [theirs["bounding_box"]["min"], theirs["bounding_box"]["max"]]


def test_tags_survive_files(mesh_path, tmp_path):
    mesh = limsurf.read_mesh(mesh_path("cube_creases"))
    assert mesh.creases.shape[1] == 3 and len(mesh.creases) > 0
    out = tmp_path / "copy.obj"
    limsurf.write_mesh(out, mesh)
    again = limsurf.read_mesh(out)
    assert np.array_equal(again.V, mesh.V) and np.array_equal(again.creases, mesh.creases)
    built = limsurf.Mesh(mesh.V, mesh.F, creases=mesh.creases, corners=mesh.corners)
    assert np.array_equal(built.creases, mesh.creases)


def test_binary_ply_round_trip(mesh_path, tmp_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    out = tmp_path / "g.ply"
    limsurf.write_mesh(str(out), mesh, ply_encoding="binary-le")
    again = limsurf.read_mesh(out)
    assert np.array_equal(again.V, mesh.V) and np.array_equal(again.F, mesh.F)


@pytest.mark.parametrize("V, F, pattern", [
    (CUBE_V, np.where(CUBE_F == 6, 8, CUBE_F), r"F\[1, 2\] = 8: vertex index out of range \(V has 8 rows\)"),
    (CUBE_V, CUBE_F - 1, r"F\[0, 0\] = -1: vertex index out of range"),
    (CUBE_V, CUBE_F.astype(float), r"F: expected integer vertex indices, got dtype float64"),
    (CUBE_V, CUBE_F[:, :2], r"F: faces need at least 3 corners"),
    (CUBE_V, [[0, 1, 2], [0, 1]], r"F\[1\]: a face needs a sequence of at least 3"),
    (CUBE_V[:, :2], CUBE_F, r"V: expected shape \(n, 3\), got \(8, 2\)"),
    (np.where(np.arange(24).reshape(8, 3) == 13, np.nan, CUBE_V), CUBE_F, r"V\[4, 1\] = nan: values must be finite"),
    (CUBE_V.astype(complex), CUBE_F, r"V: expected real numbers, got dtype complex128"),
    ("not an array", CUBE_F, r"V: expected real numbers, got dtype <U12"),
])
def test_bad_arrays_raise_input_errors_naming_array_row_and_problem(V, F, pattern):
    with pytest.raises(limsurf.InputError, match=pattern):
        limsurf.Mesh(V, F)


def test_errors_are_a_hierarchy_of_python_exceptions():
    assert issubclass(limsurf.InputError, limsurf.Error) and issubclass(limsurf.InputError, ValueError)
    assert issubclass(limsurf.TopologyError, limsurf.Error)
    assert issubclass(limsurf.UnsupportedError, NotImplementedError)
    assert issubclass(limsurf.Error, RuntimeError)


def test_unusable_connectivity_is_a_topology_error():
    V = np.zeros((5, 3))
    V[:, 0] = np.arange(5)
    V[3:, 1] = 1
    with pytest.raises(limsurf.TopologyError, match=r"edge \(0, 1\) is shared by 3 faces \(non-manifold\)"):
        limsurf.Mesh(V, [[0, 1, 3], [1, 0, 4], [0, 1, 2]])


def test_file_errors_name_file_and_line(tmp_path):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    with pytest.raises(limsurf.InputError, match=r"bad\.obj:4:"):
        limsurf.read_mesh(bad)
    with pytest.raises(limsurf.InputError, match="cannot open"):
        limsurf.read_mesh(tmp_path / "missing.obj")


def test_isolated_vertices_are_refused_or_dropped_with_a_warning():
    V = np.vstack([CUBE_V, [[5.0, 5.0, 5.0]]])
    with pytest.raises(limsurf.Error, match="8"):
        limsurf.Mesh(V, CUBE_F)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mesh = limsurf.Mesh(V, CUBE_F, isolated="drop")
    assert mesh.num_vertices == 8
    assert any(issubclass(w.category, limsurf.MeshWarning) for w in caught)


def test_converting_a_million_faces_needs_no_python_loop():
    n = 500
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    V = np.column_stack([i.ravel(), j.ravel(), np.zeros(n * n)]).astype(float)
    a = (i[:-1, :-1] * n + j[:-1, :-1]).ravel()
    quads = np.column_stack([a, a + n, a + n + 1, a + 1])
    mesh = limsurf.Mesh(V, quads)
    fine = limsurf.subdivide(mesh, "bilinear", 1)
    assert fine.num_faces == 4 * mesh.num_faces
    F = fine.F  # ~1M × 4, one copy in C++
    assert F.shape == (fine.num_faces, 4) and F.dtype == np.int32


def test_submesh_keeps_faces_and_says_where_they_came_from(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    keep = np.arange(mesh.num_faces) % 3 != 0
    part, vertex_origin, face_origin = limsurf.submesh(mesh, keep)
    assert vertex_origin.dtype == np.int32 and face_origin.dtype == np.int32
    assert np.array_equal(face_origin, np.flatnonzero(keep))
    assert np.array_equal(vertex_origin[part.F], mesh.F[face_origin])
    assert np.array_equal(part.V, mesh.V[vertex_origin])
    same, _, _ = limsurf.submesh(mesh, keep.astype(np.int64))  # integers select as booleans do
    assert np.array_equal(same.F, part.F)


def test_submesh_splits_a_vertex_where_kept_faces_only_touch():
    # a 2×2 grid keeping two diagonal quads: they meet at the centre vertex only
    V = np.array([[x, y, 0.0] for y in range(3) for x in range(3)])
    F = np.array([[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]])
    part, vertex_origin, _ = limsurf.submesh(limsurf.Mesh(V, F), [True, False, False, True])
    assert part.num_vertices == 8 and np.count_nonzero(vertex_origin == 4) == 2
    assert limsurf.info(part)["num_components"] == 2


@pytest.mark.parametrize("keep, pattern", [
    ([True, False], r"keep: expected shape \(4,\)"),
    ([0.5, 1.0, 0.0, 1.0], "keep: expected booleans or integers"),
    ([False] * 4, "keeps no face"),
])
def test_submesh_refuses_a_bad_selection(keep, pattern):
    V = np.array([[x, y, 0.0] for y in range(3) for x in range(3)])
    F = np.array([[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]])
    with pytest.raises(limsurf.InputError, match=pattern):
        limsurf.submesh(limsurf.Mesh(V, F), keep)
