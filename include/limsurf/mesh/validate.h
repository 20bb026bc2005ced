// Validation of a PolygonSoup: every problem, not just the first.
//
// validate() never throws on bad data; it lists each problem with its
// location. build_control_mesh() (control_mesh.h) calls it and throws when
// the report has errors. See docs/guide/validation.md for every check.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "limsurf/core/error.h"
#include "limsurf/mesh/polygon_soup.h"

namespace limsurf {

/// The kinds of problem validate() detects.
enum class Problem {
    NoFaces,                  ///< error: the mesh has no faces
    FaceTooSmall,             ///< error: a face with fewer than 3 corners
    RepeatedVertex,           ///< error: a face visits a vertex twice
    IndexOutOfRange,          ///< error: a face or tag names a vertex/face that does not exist
    NonFiniteCoordinate,      ///< error: NaN or infinite position
    NonManifoldEdge,          ///< error: an edge shared by more than 2 faces
    NonManifoldVertex,        ///< error: a vertex whose faces form several fans (bow-tie)
    InconsistentOrientation,  ///< error: two faces traverse an edge in the same direction
    NonOrientable,            ///< error: no consistent orientation exists (Möbius band)
    BadTag,                   ///< error: a crease on a non-edge, negative or non-finite sharpness
    IsolatedVertex,           ///< warning: a vertex in no face (dropped by build_control_mesh)
    DegenerateFace,           ///< warning: a face of zero area
    DuplicateFace,            ///< warning: two faces with the same vertex set
    /// warning: an edge or vertex tagged again with another sharpness (the last tag is used, as in
    /// OpenSubdiv's factory, even when it is 0)
    ConflictingTag
};

/// Warnings leave the mesh usable; errors do not.
enum class Severity { Warning, Error };

/// The fixed severity of each Problem.
[[nodiscard]] Severity severity_of(Problem problem) noexcept;

/// A short stable name, e.g. "non-manifold-edge" (used in JSON output).
[[nodiscard]] const char* problem_name(Problem problem) noexcept;

/// One problem, fully described.
struct Issue {
    Problem problem;
    Severity severity;
    std::string location;  ///< "file:line", "file" or "" (in-memory data)
    std::string message;   ///< names the element, e.g. "face 7 repeats vertex 3"

    /// location + ": " + message (or just message when there is no location).
    [[nodiscard]] std::string to_string() const;
};

/// Everything validate() found, in file order within each check.
struct ValidationReport {
    std::vector<Issue> issues;

    [[nodiscard]] std::size_t num_errors() const noexcept;
    [[nodiscard]] std::size_t num_warnings() const noexcept;
    [[nodiscard]] bool has_errors() const noexcept { return num_errors() > 0; }

    /// One line: the first error and how many more problems there are.
    [[nodiscard]] std::string summary() const;

    /// @throws TopologyError (connectivity problems) or InputError (anything else)
    ///   with summary() as the message, when the report has errors.
    void throw_if_errors() const;
};

/// Options for validate().
struct ValidateOptions {
    /// A face is degenerate when its vector area is at most this fraction of
    /// the squared bounding-box diagonal. >= 0.
    double degenerate_area_tolerance = 1e-14;
};

/// @brief Checks @p soup for every problem listed in Problem.
/// @details Connectivity checks that depend on earlier ones are skipped when
///   those fail (orientation is not checked across a non-manifold edge).
/// @return the report; never throws on bad data.
[[nodiscard]] ValidationReport validate(const PolygonSoup& soup, const ValidateOptions& options = {});

}  // namespace limsurf
