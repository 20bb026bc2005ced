// The C2g0 scheme (Chen, Grundel, Yu, "A flexible C² subdivision scheme on the sphere", 2017,
// §1.2 and §2): the three-directional box spline with directions [1,0], [0,1], [1,1] each
// repeated three times (C⁴, degree-7 pieces), plus valence-3 rules that make the surface C² with
// flexible curvature there. It refines closed triangle meshes whose vertices have valence 3 or 6
// (subdivided tetrahedra, regular tori: genus 0 and 1). docs/schemes.md, "C2g0".
//
// Every weight is an exact rational (the paper's values); the doubles the refinement uses are the
// correctly rounded quotients.
#pragma once

#include <array>
#include <cstdint>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"

namespace limsurf {

/// An exact weight num/den.
struct Rational {
    std::int64_t num = 0;
    std::int64_t den = 1;
    [[nodiscard]] double value() const noexcept { return static_cast<double>(num) / static_cast<double>(den); }
};

/// @brief The regular rules: the mask of symbol (1.3),
///   â(z1, z2) = z1⁻³ z2⁻³ (1 + z1)³ (1 + z2)³ (1 + z1 z2)³ / 128, split into its even part (the
///   vertex rule, on the 1-ring) and its three odd parts (the edge rule, on the 1-rings of both
///   ends). Named by the position of a stencil vertex relative to the edge (p, q) with opposite
///   vertices r and s:
struct C2g0RegularRules {
    Rational vertex_self{7, 16};       ///< the vertex itself
    Rational vertex_neighbour{3, 32};  ///< each of its 6 neighbours
    Rational edge_end{39, 128};        ///< p and q
    Rational edge_opposite{9, 64};     ///< r and s, the third corners of the edge's two triangles
    Rational edge_side{3, 128};        ///< the 4 further neighbours of p or q next to r or s
    Rational edge_far{1, 128};         ///< the 2 neighbours of p (q) opposite q (p) in its 1-ring
};

/// @brief The valence-3 rules of Fig. 3 (the rows of matrix (2.2)) for an extraordinary vertex c with
///   neighbours r₀, r₁, r₂ (counter-clockwise), tᵢ the vertex opposite c in rᵢ's 1-ring, and uᵢ the
///   third corner of the triangle across edge (rᵢ, rᵢ₊₁) from c:
///   vertex rule  c' = z c + s Σ rᵢ + t Σ tᵢ + u Σ uᵢ;
///   edge rule on (c, rᵢ): a c + b rᵢ + c (rᵢ₊₁ + rᵢ₋₁) + e tᵢ + d (uᵢ + uᵢ₋₁).
/// The values are the paper's choice (end of §2.7), which makes the four parameter-dependent
/// eigenvalues vanish.
struct C2g0Valence3Rules {
    Rational z{8901, 57792};
    Rational s{12606, 57792};
    Rational t{885, 57792};
    Rational u{2806, 57792};
    Rational a{233, 896};
    Rational b{248, 896};
    Rational c{171, 896};
    Rational d{29, 896};
    Rational e{15, 896};
};

/// @brief Refuses a topology the C2g0 rules do not apply to, before any work, naming the element:
///   a boundary edge, a face that is not a triangle, a vertex of valence other than 3 or 6, a tagged
///   edge, vertex or hole (C2g0 has no crease rules), or two adjacent valence-3 vertices (the rules of
///   each read the other's one-ring as regular; the tetrahedron itself, whose four vertices all touch,
///   is refused, its once-subdivided version accepted).
/// @throws UnsupportedError with the ErrorElement of the offending face or vertex
void require_c2g0_topology(const Topology& topology);

}  // namespace limsurf
