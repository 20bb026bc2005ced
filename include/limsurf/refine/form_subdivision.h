// Subdivision of discrete 1- and 2-forms (Subdivision Exterior Calculus, de Goes, Desbrun,
// Meyer, DeRose 2016, §3.1): the matrices S1 (edges) and S2 (faces) that go with a step's S0 so
// that subdivision commutes with the exterior derivatives,
//
//     d0' S0 = S1 d0   and   d1' S1 = S2 d1      (Eq. 6; primes: the child level),
//
// exactly, at every level. 1-forms are integrals along edges (an edge runs from its lower to its
// higher vertex), 2-forms integrals over faces (docs/conventions.md "Edges and incidence"), so each
// row of S2 sums to 1/4 and each column to 1: a coarse face hands its integral to its children.
//
// Rules (docs/sec.md "Form subdivision" lists them all): Loop's 2-forms are the half-box spline
// rules with β_n = min(1/4, 1/(8(1 − cos 2π/n))), Catmull–Clark's the Doo–Sabin-like rules; each
// 1-form rule is the exact part that S0 forces plus the face circulations that S2 forces. Both
// with boundaries (smooth boundary curves; one-face corners kept fixed under EdgeAndCorner).
#pragma once

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/refine/level.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/scheme/tuned_weights.h"

namespace limsurf {

/// The form operators of one refinement step.
struct FormSubdivision {
    SparseMatrix S1;  ///< #E_child × #E_parent: child edge integrals = S1 · parent edge integrals
    SparseMatrix S2;  ///< #F_child × #F_parent: child face integrals = S2 · parent face integrals
};

/// @brief Refuses what form subdivision has no rules for, before any work.
/// @throws UnsupportedError for schemes other than Loop and Catmull–Clark; Catmull–Clark on a
///   face that is not a quad (refine once first: every child face is a quad); creases, corners
///   or holes (the paper leaves creases to future work), naming the first tagged element; tuned
///   Catmull–Clark weights; an interior vertex with fewer than three faces
void require_form_rules(const Topology& parent, SchemeKind kind, const SchemeOptions& options = {},
                        const TunedWeights& weights = {});

/// @brief S1 and S2 of the step from @p parent to @p child.
/// @pre @p child is refine(parent, kind, options).topology (checked by its element counts)
/// @throws as require_form_rules; InputError when @p child is not the child of @p parent
[[nodiscard]] FormSubdivision form_subdivision(const Topology& parent, const Topology& child, SchemeKind kind,
                                               const SchemeOptions& options = {});

/// @brief One refinement step with the form operators filled in (Level::S1, Level::S2).
/// @throws as require_form_rules
[[nodiscard]] Level refine_with_forms(const Topology& parent, SchemeKind kind, const SchemeOptions& options = {},
                                      const TunedWeights& weights = {});

}  // namespace limsurf
