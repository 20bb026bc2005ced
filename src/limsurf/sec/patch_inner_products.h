// The subdivision inner products (SEC Eq. 12, 16) assembled control face by control face.
//
// Every quantity of Eq. 12 is a sum over the level-L faces, and the level-L faces inside control
// face f — their positions, and the values A_k^L gives their vertices, edges and faces — depend
// only on the control elements of f's ring (f and the faces sharing a vertex with it). So
//
//     M_k^0 = Σ_f  R_{k,f}ᵀ (A_k^L|_f)ᵀ M_k^L|_f A_k^L|_f R_{k,f},
//
// with A_k^L|_f the rows of A_k^L for the level-L elements inside f, restricted to the columns of
// f's ring (R_{k,f} gathers those). The restricted rows depend only on the ring's connectivity:
// they are computed once per distinct ring, by refining the ring alone with the engine
// (Hierarchy with forms), and shared by every face with that ring (on a mesh refined once or
// more, nearly every face has the regular ring). No level-L mesh of the whole surface is built;
// faces are processed in parallel; the result equals pulled_back_inner_products up to rounding
// (tests/sec/inner_products_test.cpp checks it on every bundled mesh).
#pragma once

#include <functional>
#include <optional>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/sec/inner_products.h"

namespace limsurf::detail {

/// @brief Refuses a mesh on which the ring stencils cannot assemble Sec: no form rules for
///   @p scheme there (require_form_rules), or a face or vertex beyond max_limit_size (a ring
///   stencil holds every level-L element around a valence-n vertex against its O(n) ring vertices,
///   bounded as the limit basis is).
/// @throws UnsupportedError as require_form_rules and require_local_size
void require_ring_stencils(const Topology& topology, SchemeKind scheme, const SchemeOptions& options);

/// @brief M_0^0, M_1^0, M_2^0 of Sec (Eq. 12), or of SecSnap (Eq. 16) when @p snap, at
///   @p level >= 1 for the control mesh (@p topology, @p X0) (#V × 3).
/// @pre require_ring_stencils(topology, scheme, options) passed; X0.rows() == #V
/// @param num_threads threads (0: hardware concurrency)
/// @param required    throw instead of returning nullopt
/// @return nullopt when some face's ring cannot be refined on its own (not expected: rings that
///   touch themselves are split into a mesh first); the caller then assembles from the hierarchy
/// @throws NumericalError naming the control face when a level-L face inside it has zero area;
///   UnsupportedError naming the face whose ring cannot be refined, when @p required
[[nodiscard]] std::optional<InnerProducts> patch_inner_products(const Topology& topology, const Points& X0,
                                                                SchemeKind scheme, const SchemeOptions& options,
                                                                int level, bool snap, int num_threads, bool required);

/// @brief The load vector b = (A_0^L)ᵀ M_0^L f(X^L) of Sec (SecSnap when @p snap) by the same
///   ring stencils: b = Σ_f R_fᵀ (A_0^L|_f)ᵀ (m_f ⊙ f(X^L|_f)), with m_f the level-L vertex masses'
///   shares from the level-L faces inside f (the polygonal M_0^L is diagonal). No level-L mesh is
///   built; f is called with blocks of points (a level-L vertex on a control edge or corner once
///   per control face around it), faces are summed in order (the same bits on any thread count).
/// @pre as patch_inner_products
/// @return nullopt when some face's ring cannot be refined on its own
/// @throws as patch_inner_products; InputError when f returns the wrong number of values or a
///   non-finite one
[[nodiscard]] std::optional<Eigen::VectorXd> patch_load_vector(const Topology& topology, const Points& X0,
                                                               SchemeKind scheme, const SchemeOptions& options,
                                                               int level, bool snap, int num_threads, bool required,
                                                               const std::function<Eigen::VectorXd(const Points&)>& f);

}  // namespace limsurf::detail
