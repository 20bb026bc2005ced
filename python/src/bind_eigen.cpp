// The eigen-analysis of a scheme around one extraordinary vertex (analysis/eigen_analysis.h,
// docs/eigen.md, docs/guide/eigen.md): the dict of `limsurf eigen --json` with the same keys, an
// eigenvalue as a Python complex instead of {re, im, abs}, and what the JSON leaves out as numpy
// arrays: the local subdivision matrix, each eigenvalue's eigenvectors and the sampled
// characteristic map (positions and faces, for plotting).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/analysis/eigen_analysis.h"
#include "limsurf/scheme/tuned_weights.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

py::dict eigenvalue_dict(const EigenvalueEntry& e) {
    return py::dict("value"_a = e.value,
                    "frequency"_a = e.frequency < 0 ? py::object(py::none()) : py::int_(e.frequency),
                    "algebraic"_a = e.algebraic, "geometric"_a = e.geometric, "jordan_blocks"_a = e.jordan_blocks,
                    "eigenvectors"_a = to_numpy(e.eigenvectors));
}

py::dict test_dict(const SmoothnessTest& t) {
    return py::dict("checked"_a = t.checked, "passed"_a = t.checked ? py::object(py::bool_(t.passed)) : py::none(),
                    "detail"_a = t.detail);
}

/// The statistics `limsurf eigen --json` prints, and the sampled map itself where there is one.
py::dict characteristic_map_dict(const CharacteristicMap& m) {
    py::dict out("evaluated"_a = m.evaluated);
    if (!m.evaluated) {
        out["reason"] = m.reason;
        return out;
    }
    out["min_jacobian"] = m.min_jacobian;
    out["max_jacobian"] = m.max_jacobian;
    out["winding_number"] = m.winding_number;
    out["samples"] = m.samples;
    out["resolution"] = m.resolution;
    out["positions"] = to_numpy(m.positions);
    std::vector<Index> offsets{0};
    std::vector<Index> corners;
    for (const std::vector<Index>& face : m.faces) {
        corners.insert(corners.end(), face.begin(), face.end());
        offsets.push_back(static_cast<Index>(corners.size()));
    }
    out["faces"] = faces_array(offsets, corners);
    return out;
}

py::dict spectrum_dict(const std::string& scheme, const SchemeSpectrum& s) {
    py::list values;
    for (const EigenvalueEntry& e : s.eigenvalues) {
        values.append(eigenvalue_dict(e));
    }
    py::array_t<int> sector(static_cast<py::ssize_t>(s.sector.size()));
    std::copy(s.sector.begin(), s.sector.end(), sector.mutable_data());
    return py::dict("scheme"_a = scheme, "valence"_a = s.request.valence, "boundary"_a = s.request.boundary,
                    "rings"_a = s.rings, "size"_a = s.S.rows(), "symmetry_residual"_a = s.symmetry_residual,
                    "dominant"_a = s.dominant, "subdominant"_a = s.subdominant,
                    "subdominant_multiplicity"_a = s.subdominant_multiplicity, "subsubdominant"_a = s.subsubdominant,
                    "subsubdominant_multiplicity"_a = s.subsubdominant_multiplicity, "eigenvalues"_a = values,
                    "characteristic_map"_a = characteristic_map_dict(s.characteristic_map),
                    "tests"_a = py::dict("c1_spectrum"_a = test_dict(s.c1_spectrum), "c1"_a = test_dict(s.c1),
                                         "bounded_curvature"_a = test_dict(s.bounded_curvature),
                                         "c2_necessary"_a = test_dict(s.c2_necessary)),
                    "S"_a = to_numpy(Eigen::MatrixXd(s.S)), "sector"_a = sector);
}

constexpr const char* eigen_doc = R"(The spectrum of the scheme's local subdivision matrix around one
extraordinary vertex of this valence (Doo–Sabin: one face of this degree) and the classical smoothness
verdicts — `limsurf eigen --json`'s dict (docs/guide/eigen.md): 'scheme', 'valence', 'boundary', 'rings',
'size', 'symmetry_residual', 'dominant', 'subdominant' (λ), 'subdominant_multiplicity', 'subsubdominant',
'subsubdominant_multiplicity', 'eigenvalues' (by decreasing modulus: dicts 'value' (complex), 'frequency'
(the Fourier block; None without rotational symmetry), 'algebraic', 'geometric', 'jordan_blocks' and
'eigenvectors', a complex128 array size × geometric over the neighbourhood), 'characteristic_map'
('evaluated'; then 'min_jacobian', 'max_jacobian', 'winding_number', 'samples' (those of the ring segment,
where det DΦ is checked), 'resolution' r and the map as a mesh: 'positions' (the points (i, j)/r of each
face at the vertex, face after face, z = 0) and 'faces'; else 'reason') and 'tests' ('c1_spectrum', 'c1', 'bounded_curvature',
'c2_necessary', each {'checked', 'passed' (None when not checked), 'detail'}); also 'S', the local
subdivision matrix (size × size float64, sector-major: the centre, then sector 0's vertices, sector 1's in
the same order, ...) and 'sector' (int32, each neighbourhood vertex's sector, −1 for the centre).
scheme: 'catmull-clark', 'loop', 'doo-sabin' or 'c2g0' (valence 3 or 6); boundary: the vertex on a
boundary with valence − 1 faces (Catmull–Clark, Loop); weights: tuned Catmull–Clark weights of the vertex,
(alpha, beta, gamma) or a dict W; rings: face rings of the neighbourhood (1..8; 0: what the scheme needs;
fewer give the spectrum but no characteristic map, so 'c1' is not checked).
Raises limsurf.InputError for a request the analysis refuses, limsurf.NumericalError for too few rings.)";

}  // namespace

void bind_eigen(py::module_& m) {
    m.def(
        "eigen_analysis",
        [](const std::string& scheme, int valence, bool boundary, const std::optional<py::object>& weights, int rings) {
            EigenRequest request;
            request.scheme = scheme_from(scheme);
            request.valence = valence;
            request.boundary = boundary;
            request.rings = rings;
            if (weights && !weights->is_none()) {
                request.weights = vertex_weights_from(*weights, "weights");
            }
            std::optional<SchemeSpectrum> spectrum;
            {
                const py::gil_scoped_release release;
                spectrum = analyse_scheme(request);
            }
            return spectrum_dict(scheme, *spectrum);
        },
        "scheme"_a, "valence"_a, py::kw_only(), "boundary"_a = false, "weights"_a = py::none(), "rings"_a = 0,
        eigen_doc);
}

}  // namespace limsurf::python
