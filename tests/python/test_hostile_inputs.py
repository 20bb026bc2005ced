"""What a sweep of every function of the module with hostile arguments found (2026-12-06, ~1,900
calls): each call here crashed the interpreter, ran for ever, returned nan, or silently ignored its
argument before, and now raises a clear error or returns the right thing."""
import numpy as np
import pytest

import limsurf


def test_rigid_body_modes_of_no_points_is_an_error_not_a_crash():
    with pytest.raises(limsurf.InputError, match=r"rigid_body_modes: X has 0 × 3 entries"):
        limsurf.rigid_body_modes(np.zeros((0, 3)))


def test_shell_levels_are_bounded(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("shell_scordelis_lo"))
    with pytest.raises(limsurf.InputError, match=r"shell: levels must be in 0\.\.6, got 30"):
        limsurf.shell(mesh, "catmull-clark", levels=30, E=4.32e8, nu=0.0, thickness=0.25, gravity=90.0,
                      supports=[(True, "xyz")])


def test_a_spontaneous_curvature_that_is_not_finite_or_overflows_is_refused(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("sphere_tris"))
    with pytest.raises(limsurf.InputError, match=r"spontaneous_curvature: H0 must be a finite number, not nan"):
        limsurf.shape_functionals(mesh, "loop", spontaneous_curvature=np.nan)
    with pytest.raises(limsurf.NumericalError, match=r"the Helfrich energy with H0 = 1e\+308 is not finite"):
        limsurf.shape_functionals(mesh, "loop", spontaneous_curvature=1e308)
    with pytest.raises(limsurf.InputError, match=r"spontaneous curvature H0 = 1e\+308: H0² A0 overflows"):
        limsurf.minimize_membrane(mesh, "loop", area=4 * np.pi, reduced_volume=0.9, spontaneous_curvature=1e308)


def test_tiny_membrane_targets_are_refused(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("octahedron"))
    with pytest.raises(limsurf.InputError, match=r"reduced volume v0 = 9\.9999999999999995e-08: must be at least"):
        limsurf.minimize_membrane(mesh, "loop", area=4 * np.pi, reduced_volume=1e-7)
    with pytest.raises(limsurf.InputError, match=r"area A0 = 3.8725919148493183e-121: must lie in \[1e-100, 1e\+100\]"):
        limsurf.minimize_membrane(mesh, "loop", area=2.0**-400, reduced_volume=0.9)


def test_a_one_form_that_overflows_is_an_error_not_nan(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("cube"))
    with pytest.raises(limsurf.NumericalError, match=r"the vectors of this 1-form are not finite"):
        limsurf.one_form_vectors(mesh, "catmull-clark", np.ones(12) * 1e300, level=1)


def test_a_plate_whose_deflection_underflows_is_an_error_not_nan(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("plate_asym"))
    with pytest.raises(limsurf.NumericalError, match=r"plate: Navier's deflection .* too small or too large"):
        limsurf.plate(mesh, "catmull-clark", 1e4, E=1e308)


def test_reverse_refuses_a_tolerance_that_is_not_a_number(mesh_path):
    fine = limsurf.subdivide(limsurf.read_mesh(mesh_path("cube")), "catmull-clark", 2)
    for tolerance in (np.nan, -1.0, np.inf):
        with pytest.raises(limsurf.InputError, match=r"the tolerance must be a finite number >= 0"):
            limsurf.reverse_catmull_clark(fine, tolerance=tolerance)


def test_negative_resolutions_and_thread_counts_are_refused(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("cube"))
    with pytest.raises(limsurf.InputError, match=r"resolution: expected 0 \(automatic\) or 1\.\.1024, got -5"):
        limsurf.tessellate(mesh, "catmull-clark", resolution=-5)
    with pytest.raises(limsurf.InputError, match=r"threads: expected 0 \(all cores\)"):
        limsurf.tessellate(mesh, "catmull-clark", threads=-1)
    with pytest.raises(limsurf.InputError, match=r"threads: expected 0 \(all cores\)"):
        limsurf.self_intersections(mesh, "catmull-clark", threads=-7)


def test_heat_geodesics_of_no_source_sets_and_a_bad_level(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("cube"))
    heat = limsurf.HeatGeodesics(mesh, "catmull-clark", level=2)
    assert heat.distances([]).shape == (8, 0)  # CHOLMOD printed an error on stderr for it
    with pytest.raises(limsurf.InputError, match=r"^the level must be in \[0, 8\], got -1"):
        limsurf.geodesic_distance(mesh, "catmull-clark", 0, level=-1)


def test_complex_creases_and_empty_index_lists(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("cube"))
    V, F = np.array(mesh.V), np.array(mesh.F)
    with pytest.raises(limsurf.InputError, match=r"creases: expected real numbers, got dtype complex128"):
        limsurf.Mesh(V, F, creases=np.array([[0, 1, 2 + 5j]]))
    assert limsurf.Mesh(V, F, holes=[]).num_faces == 6  # an empty list is float64 in numpy


def test_picture_and_gltf_files_need_their_extension(mesh_path, tmp_path):
    # A .bmp got PNG bytes, a .obj glTF bytes; `limsurf render -o` refuses both.
    mesh = limsurf.read_mesh(mesh_path("cube"))
    with pytest.raises(limsurf.InputError, match=r"unknown format '\.bmp' \(expected \.png or \.glb\)"):
        limsurf.render(mesh, "catmull-clark", size=(32, 32), resolution=2, output=tmp_path / "q.bmp")
    V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    with pytest.raises(limsurf.InputError, match=r"expected a \.glb file \(glTF binary\), got '\.obj'"):
        limsurf.write_glb(tmp_path / "q.obj", V, np.array([[0, 1, 2]]))
    assert not any(tmp_path.iterdir())


def test_self_intersection_does_not_depend_on_the_size(mesh_path):
    # The triangle tests multiply coordinates: at 1e200 they overflowed and the cube "intersected"
    # itself in 50 818 pairs; at 1e300 its diagonal overflowed (an error about the weld tolerance).
    mesh = limsurf.read_mesh(mesh_path("cube"))
    unit = limsurf.self_intersections(mesh, "catmull-clark")
    for scale in (1e-200, 1e100, 1e200, 1e300):
        scaled = limsurf.self_intersections(mesh, "catmull-clark", X=np.array(mesh.V) * scale)
        assert (scaled["intersects"], scaled["intersecting_pairs"]) == (False, 0), scale
        assert scaled["triangles"] == unit["triangles"]
    # A surface that does meet itself meets itself at any size (as in tests/apps: a vertex pulled through).
    ico = limsurf.read_mesh(mesh_path("icosahedron"))
    V = np.array(ico.V)
    V[0] = -3.0 * V[0] + 0.3 * V[5]
    crossing = limsurf.self_intersections(ico, "loop", X=V)
    assert crossing["intersects"]
    huge = limsurf.self_intersections(ico, "loop", X=V * 2.0**800)
    assert huge["intersecting_pairs"] == crossing["intersecting_pairs"]
    assert huge["control_faces"] == crossing["control_faces"]


def test_a_memory_budget_must_be_positive(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("cube"))
    with pytest.raises(limsurf.InputError, match=r"the memory budget \(max_memory\) must be positive, got -1"):
        limsurf.poisson(mesh, "catmull-clark", lambda P: P[:, 0], method="sec", level=1, reference_level=2,
                        max_memory=-1)


def test_arguments_the_method_does_not_use_are_refused(mesh_path):
    """degree and tiles are iga's quadrature: with sec or dec they were ignored without a word; a
    gradient_level of -1 was the library's 'not given' and silently meant None."""
    mesh = limsurf.read_mesh(mesh_path("cube"))
    with pytest.raises(limsurf.InputError, match=r"degree applies to method 'iga', not to 'sec'"):
        limsurf.poisson(mesh, "catmull-clark", np.arange(8.0), degree=4)
    with pytest.raises(limsurf.InputError, match=r"tiles applies to method 'iga', not to 'dec'"):
        limsurf.geodesic_distance(mesh, "catmull-clark", 0, method="dec", tiles=2)
    with pytest.raises(limsurf.InputError, match=r"degree applies to method 'iga', not to 'secsnap'"):
        limsurf.HeatGeodesics(mesh, "catmull-clark", method="secsnap", level=1, degree=3)
    with pytest.raises(limsurf.InputError, match=r"gradient_level must be >= 0 \(or None\), not -1"):
        limsurf.geodesic_distance(mesh, "catmull-clark", 0, level=1, gradient="subdivided", gradient_level=-1)
    iga = limsurf.geodesic_distance(mesh, "catmull-clark", 0, method="iga", degree=2, tiles=1)
    assert iga["quadrature"] == {"degree": 2, "tiles": 1}
    default = limsurf.poisson(mesh, "catmull-clark", np.arange(8.0), method="iga")
    assert default["quadrature"] == {"degree": 8, "tiles": 6}


def test_a_complex_macroscopic_deformation_is_refused(mesh_path):
    """The imaginary part was dropped with only numpy's ComplexWarning."""
    mesh = limsurf.read_mesh(mesh_path("rve_block"))
    with pytest.raises(limsurf.InputError, match=r"macro_deformation: expected real numbers, got dtype complex128"):
        limsurf.elasticity(mesh, macro_deformation=np.eye(2) * (1 + 0.5j))


def test_conflicting_repeated_tags_warn_and_the_last_wins(mesh_path):
    """Two tags of one edge with different sharpness were taken without a word, and a later 0 was
    skipped (OpenSubdiv, and now limsurf, use the last tag)."""
    mesh = limsurf.read_mesh(mesh_path("cube"))
    V, F = np.array(mesh.V), np.array(mesh.F)
    a, b = F[0][0], F[0][1]
    with pytest.warns(limsurf.MeshWarning, match=r"crease \(.*\) has sharpness 0 here and 2 at tag 0; the last tag is used"):
        cleared = limsurf.Mesh(V, F, creases=[(a, b, 2.0), (b, a, 0.0)])
    assert len(cleared.creases) == 0
    with pytest.warns(limsurf.MeshWarning, match=r"corner 3 has sharpness 1\.5 here and 10 at tag 0"):
        later = limsurf.Mesh(V, F, corners=[(3, 10.0), (3, 1.5)])
    assert later.corners.tolist() == [[3.0, 1.5]]


def test_a_level_is_refused_by_methods_without_one(mesh_path):
    """level (SEC's L) with dec, decsnap or iga was ignored without a word, as --level in the CLI was."""
    mesh = limsurf.read_mesh(mesh_path("cube"))
    with pytest.raises(limsurf.InputError, match=r"level applies to method 'sec' and 'secsnap', not to 'dec'"):
        limsurf.operators(mesh, "catmull-clark", method="dec", level=2)
    with pytest.raises(limsurf.InputError, match=r"not to 'iga'"):
        limsurf.poisson(mesh, "catmull-clark", np.arange(8.0), method="iga", level=2)
    with pytest.raises(limsurf.InputError, match=r"not to 'decsnap'"):
        limsurf.geodesic_distance(mesh, "catmull-clark", 0, method="decsnap", level=1)
    with pytest.raises(limsurf.InputError, match=r"not to 'dec'"):
        limsurf.harmonic_basis(mesh, "catmull-clark", method="dec", level=1)
    with pytest.raises(limsurf.InputError, match=r"not to 'dec'"):
        limsurf.design_vector_field(mesh, "catmull-clark", sources=[(0, 1.0)], method="dec", level=1)
    assert limsurf.poisson(mesh, "catmull-clark", np.arange(8.0))["level"] == 3  # the default, for sec
    assert limsurf.operators(mesh, "catmull-clark", method="dec")["d0"].shape == (12, 8)


def test_a_weight_too_stiff_for_the_energy_is_refused(mesh_path):
    """weight=2**63 failed as 'not positive definite (degenerate geometry?)' on genus2, and on the cube a
    weight of 1e18 gave 4 000 times the minimal energy without an error."""
    for name in ("genus2", "cube"):
        mesh = limsurf.read_mesh(mesh_path(name))
        with pytest.raises(limsurf.InputError, match=r"times stiffer than the energy: .* may have here is about"):
            limsurf.design_vector_field(mesh, "catmull-clark", sources=[(0, 1.0)], sinks=[(6, 1.0)], weight=2**63)


def test_a_ragged_list_is_an_error_not_a_crash(mesh_path):
    # pybind11's array ensure() returns a null array when numpy refuses, and that null array was used:
    # a segmentation fault (tests/python/adversarial/sweep.py, 2026-12-06).
    mesh = limsurf.read_mesh(mesh_path("cube"))
    with pytest.raises(limsurf.InputError, match=r"^X: not an array of numbers \(got list: ValueError: setting an "
                                                 r"array element with a sequence"):
        limsurf.volume(mesh, "catmull-clark", X=[[0, 1], [2]])
    with pytest.raises(limsurf.InputError, match=r"^V: not an array of numbers"):
        limsurf.Mesh([[0.0, 1.0], [2.0]], [[0, 1, 2]])
    with pytest.raises(limsurf.InputError, match=r"^rhs: not an array of numbers"):
        limsurf.poisson(mesh, "catmull-clark", [[1.0], [2.0, 3.0]], method="dec")


def test_values_a_binding_converts_itself_are_named(mesh_path):
    # pybind11's cast_error (a RuntimeError naming only the C++ type, e.g. "Unable to cast Python instance of
    # type <class 'numpy.float64'> to C++ type 'int'") for elements the bindings convert themselves.
    cube = limsurf.read_mesh(mesh_path("cube"))
    with pytest.raises(limsurf.InputError, match=r"^sources: expected a vertex index, got float64 nan"):
        limsurf.design_vector_field(cube, "catmull-clark", sources=np.full((3, 3), np.nan), level=1)
    with pytest.raises(limsurf.InputError, match=r"^sinks \(value, weight\): expected a number, got str 'a'"):
        limsurf.design_vector_field(cube, "catmull-clark", sinks=[(0, "a")], level=1)
    with pytest.raises(limsurf.InputError, match=r"^strokes: expected a path of vertex indices, got float 1\.5"):
        limsurf.design_vector_field(cube, "catmull-clark", strokes=[(1.5, 1.0)], level=1)
    block = limsurf.read_mesh(mesh_path("rve_block"))
    with pytest.raises(limsurf.InputError, match=r"^clamp: expected a side name \(left, right, bottom, top\), got int 3"):
        limsurf.elasticity(block, boundary="loaded", clamp=[3], tractions=[("right", (0.1, 0.0))])
    with pytest.raises(limsurf.InputError, match=r"^size: expected \(width, height\), two integers, got str 'abc'"):
        limsurf.render(cube, "catmull-clark", size="abc")
    with pytest.raises(limsurf.InputError, match=r"^view: expected iso, front, top or \(azimuth, elevation\)"):
        limsurf.render(cube, "catmull-clark", view=[1.0, 2.0, 3.0])


def test_points_near_the_largest_double_give_finite_results(mesh_path):
    # rigid_body_modes of points at 1e308 were inf and nan (the mean overflowed); reverse_catmull_clark
    # of a mesh 1e300 across reported residual_max = inf (the squares in the norm overflowed).
    cube = limsurf.read_mesh(mesh_path("cube"))
    modes = limsurf.rigid_body_modes(np.full((4, 3), 1e308))
    assert np.all(np.isfinite(modes))
    assert np.array_equal(limsurf.rigid_body_modes(cube.V * 2.0**1000), limsurf.rigid_body_modes(cube.V))
    fine = limsurf.subdivide(cube, "catmull-clark", 1)
    _, small = limsurf.reverse_catmull_clark(fine)
    _, huge = limsurf.reverse_catmull_clark(fine.with_positions(fine.V * 1e300))
    for key in ("residual_max", "residual_rms"):
        assert np.isfinite(huge["per_level"][0][key])
        assert huge["per_level"][0][key] < 1e-12 * 1e300
        assert small["per_level"][0][key] < 1e-12


def test_source_sets_that_are_rows_of_an_array(mesh_path):
    # A py::sequence's range-for gave handles into temporaries; the rows of a numpy array are new objects,
    # so the loop read freed memory: numpy's "Cannot create a circular NumPy array 'base' dependency"
    # ValueError, then a segmentation fault on the next call (tests/python/adversarial/sweep.py).
    cube = limsurf.read_mesh(mesh_path("cube"))
    heat = limsurf.HeatGeodesics(cube, "catmull-clark", method="dec")
    for _ in range(3):
        with pytest.raises(limsurf.InputError, match=r"^source_sets\[0\]: expected a vector, got 2 dimensions"):
            heat.distances(np.zeros((2, 2, 2), dtype=int))
        with pytest.raises(limsurf.InputError, match=r"^source_sets\[0\]: expected integers, got dtype float64"):
            heat.distances([[0.0, 1.0]])
    rows = heat.distances(np.array([[0, 1], [2, 3]]))
    assert np.array_equal(rows, heat.distances([[0, 1], [2, 3]]))
    field = limsurf.design_vector_field(cube, "catmull-clark", sources=np.array([[0, 1]]), level=1)
    assert np.array_equal(field["w"], limsurf.design_vector_field(cube, "catmull-clark", sources=[(0, 1.0)],
                                                                   level=1)["w"])
