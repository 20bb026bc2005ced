// The peer of the periodic homogenisation (iga-with-catmull-clark §6): FreeFem++'s body-fitted P2
// finite elements on the same cell, the unit square with the limit material interface of a bundled
// control mesh. The interface is sampled from the limit surface itself — the ptex-face sides along the
// control edges between two materials, kPerEdge points each (for square_inclusion the closed cubic
// B-spline of the creased interface vertices) — so both solvers see the same geometry up to the chords
// of that polygon. FreeFem++ solves the three unit macroscopic strains as periodic fluctuation problems
// (u = ε̄·x + ũ, ũ periodic, its mean fixed by a 1e-8 penalty) and averages σ; limsurf solves
// solve_elasticity_levels with ElasticBoundary::Periodic. The script is written here, run with
// `FreeFem++ -nw -ne`, and its numbers read back from tagged lines. Skipped without FreeFem++
// (scripts/setup.sh installs the Debian package freefem++). Three cells: a homogeneous one (C* = C,
// the script's sanity), square_inclusion (creased interface: within 1e-3 from level 0, 1.3e-5 on
// level 2 against the peer extrapolated in its chord length) and rve_block (no crease: first order).
// About 15 s on two cores.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/apps/elasticity.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/limit_basis.h"
#include "support/mesh_zoo.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

constexpr int kPerEdge = 64;  // samples of the limit interface per control edge
const ElasticMaterial kMatrix{1.0, 0.3};
const ElasticMaterial kInclusion{10.0, 0.3};

/// FreeFem++ on PATH, or empty.
fs::path find_freefem() {
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path != nullptr ? path : "");
    for (std::string dir; std::getline(dirs, dir, ':');) {
        const fs::path candidate = fs::path(dir.empty() ? "." : dir) / "FreeFem++";
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec)) {
            return candidate;
        }
    }
    return {};
}

/// A closed polygon of the limit interface (counter-clockwise around the second material) and a point
/// strictly inside that material.
struct InterfaceLoop {
    std::vector<Eigen::Vector2d> points;  ///< kPerEdge per control edge, not repeating the first
    Eigen::Vector2d inside = Eigen::Vector2d::Zero();
};

/// The (u, v) of the point at t ∈ [0, 1] along side k (corner k → corner k + 1) of a quad ptex face.
SurfacePoint on_side(Index ptex, int k, double t) {
    switch (k) {
    case 0:
        return {ptex, t, 0.0};
    case 1:
        return {ptex, 1.0, t};
    case 2:
        return {ptex, 1.0 - t, 1.0};
    default:
        return {ptex, 0.0, 1.0 - t};
    }
}

/// The faces of material != 0 numbered by the edge-connected group they belong to (-1 for material 0):
/// regions that touch only at a vertex (rve_block's grains) get their own loops.
std::vector<Index> grain_components(const Topology& topo, const std::vector<Index>& material) {
    std::vector<Index> component(material.size(), -1);
    Index count = 0;
    for (Index seed = 0; seed < topo.num_faces(); ++seed) {
        if (material[seed] == 0 || component[seed] >= 0) {
            continue;
        }
        std::vector<Index> stack{seed};
        component[seed] = count;
        while (!stack.empty()) {
            const Index f = stack.back();
            stack.pop_back();
            for (const Index e : topo.face_edges(f)) {
                for (const Index g : topo.edge_faces(e)) {
                    if (material[g] == material[f] && component[g] < 0) {
                        component[g] = count;
                        stack.push_back(g);
                    }
                }
            }
        }
        ++count;
    }
    return component;
}

/// The limit images of the control edges between a face of material 0 and one of another material,
/// chained into closed loops, one per edge-connected region; each side is taken from its non-matrix
/// face, whose counter-clockwise corners put that material on the left. Quads only (the bundled
/// cells are all quads).
std::vector<InterfaceLoop> interface_loops(const LimitBasis& basis, const Points& X,
                                           const std::vector<Index>& material) {
    const Topology& topo = basis.topology();
    const std::vector<Index> component = grain_components(topo, material);
    struct Side {
        Index face;
        int k;
        Index to;
    };
    std::map<std::pair<Index, Index>, Side> from;  // (region, start vertex) -> the side leaving it
    for (Index f = 0; f < topo.num_faces(); ++f) {
        if (material[f] == 0) {
            continue;
        }
        EXPECT_EQ(topo.face_degree(f), 4) << "face " << f;
        const auto corners = topo.face_vertices(f);
        const auto edges = topo.face_edges(f);
        for (int k = 0; k < 4; ++k) {
            for (const Index g : topo.edge_faces(edges[k])) {
                if (g != f && material[g] == 0) {
                    const bool fresh =
                        from.emplace(std::pair{component[f], corners[k]}, Side{f, k, corners[(k + 1) % 4]}).second;
                    EXPECT_TRUE(fresh) << "two interface sides of one region leave vertex " << corners[k];
                }
            }
        }
    }
    std::vector<InterfaceLoop> loops;
    while (!from.empty()) {
        InterfaceLoop loop;
        const auto [region, start] = from.begin()->first;
        Index at = start;
        do {
            const auto it = from.find({region, at});
            if (it == from.end()) {
                ADD_FAILURE() << "the interface is not closed at vertex " << at;
                return loops;
            }
            const Side side = it->second;
            from.erase(it);
            const Index ptex = basis.first_ptex_face(side.face);
            for (int i = 0; i < kPerEdge; ++i) {
                const auto p =
                    basis.evaluate(X, on_side(ptex, side.k, static_cast<double>(i) / kPerEdge), DerivativeOrder::Value);
                loop.points.emplace_back(p(0, 0), p(0, 1));
            }
            if (at == start) {
                const auto c = basis.evaluate(X, SurfacePoint{ptex, 0.5, 0.5}, DerivativeOrder::Value);
                loop.inside = Eigen::Vector2d(c(0, 0), c(0, 1));
            }
            at = side.to;
        } while (at != start);
        loops.push_back(std::move(loop));
    }
    return loops;
}

/// Shoelace area (positive counter-clockwise).
double polygon_area(const std::vector<Eigen::Vector2d>& p) {
    double a = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Eigen::Vector2d& q = p[(i + 1) % p.size()];
        a += p[i].x() * q.y() - q.x() * p[i].y();
    }
    return 0.5 * a;
}

struct PeerResult {
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    double area = 0.0;            ///< ∫ 1 over the FreeFem mesh
    double inclusion_area = 0.0;  ///< ∫ over the second material
    int triangles = 0;
    double seconds = 0.0;
};

/// The FreeFem++ script: the unit square (labels 1..4 bottom, right, top, left; `side` mesh points
/// each), each loop a piecewise-linear border through its samples with `stride` samples per mesh
/// edge, P2 × P2 periodic fluctuations, plane strain.
std::string freefem_script(const std::vector<InterfaceLoop>& loops, int side, int stride) {
    std::ostringstream s;
    s.precision(17);
    s << "border B1(t=0,1){x=t; y=0; label=1;}\n"
         "border B2(t=0,1){x=1; y=t; label=2;}\n"
         "border B3(t=0,1){x=1-t; y=1; label=3;}\n"
         "border B4(t=0,1){x=0; y=1-t; label=4;}\n";
    std::string borders = "B1(" + std::to_string(side) + ")+B2(" + std::to_string(side) + ")+B3(" +
                          std::to_string(side) + ")+B4(" + std::to_string(side) + ")";
    for (std::size_t l = 0; l < loops.size(); ++l) {
        const auto& p = loops[l].points;
        const std::string n = std::to_string(p.size());
        // One assignment per entry: FreeFem's array literals stop at 1024 entries.
        s << "real[int] px" << l << "(" << p.size() + 1 << "), py" << l << "(" << p.size() + 1 << ");\n";
        for (std::size_t i = 0; i <= p.size(); ++i) {  // closed: the first point again
            const Eigen::Vector2d& q = p[i % p.size()];
            s << "px" << l << "[" << i << "] = " << q.x() << "; py" << l << "[" << i << "] = " << q.y() << ";\n";
        }
        s << "border G" << l << "(t=0," << n << "){int i = min(int(t), " << n << "-1); real s = t - i; x = px" << l
          << "[i]*(1-s) + px" << l << "[i+1]*s; y = py" << l << "[i]*(1-s) + py" << l << "[i+1]*s; label=5;}\n";
        borders += "+G" + std::to_string(l) + "(" + std::to_string(static_cast<int>(p.size()) / stride) + ")";
    }
    s << "mesh Th = buildmesh(" << borders << ");\n"
      << "fespace Ph(Th, P0);\nPh inc = 0;\n";
    for (std::size_t l = 0; l < loops.size(); ++l) {
        s << "{ int r = Th(" << loops[l].inside.x() << ", " << loops[l].inside.y()
          << ").region; inc = inc + (region == r); }\n";
    }
    const auto lame = [&](const ElasticMaterial& m, const char* name) {
        s << "real lam" << name << " = " << m.E * m.nu / ((1 + m.nu) * (1 - 2 * m.nu)) << ", mu" << name << " = "
          << m.E / (2 * (1 + m.nu)) << ";\n";
    };
    lame(kMatrix, "m");
    lame(kInclusion, "i");
    s << R"(Ph lam = lamm + (lami - lamm)*inc;
Ph mu = mum + (mui - mum)*inc;
fespace Vh(Th, [P2,P2], periodic=[[2,y],[4,y],[1,x],[3,x]]);
Vh [u1,u2], [v1,v2];
real e11, e22, g12;
varf a([u1,u2],[v1,v2]) = int2d(Th)(lam*(dx(u1)+dy(u2))*(dx(v1)+dy(v2))
    + 2*mu*(dx(u1)*dx(v1) + dy(u2)*dy(v2) + 0.5*(dy(u1)+dx(u2))*(dy(v1)+dx(v2))) + 1e-8*(u1*v1+u2*v2));
varf b([u1,u2],[v1,v2]) = -int2d(Th)(lam*(e11+e22)*(dx(v1)+dy(v2))
    + 2*mu*(e11*dx(v1) + e22*dy(v2) + 0.5*g12*(dy(v1)+dx(v2))));
matrix A = a(Vh, Vh, solver=UMFPACK);
real area = int2d(Th)(1.0);
cout.precision(17);
cout << "LIMSURF_AREA " << area << " " << int2d(Th)(inc) << " " << Th.nt << endl;
for (int j = 0; j < 3; ++j) {
  e11 = (j == 0); e22 = (j == 1); g12 = (j == 2);
  real[int] rhs = b(0, Vh);
  u1[] = A^-1 * rhs;
  real s11 = int2d(Th)(lam*(e11+e22+dx(u1)+dy(u2)) + 2*mu*(e11+dx(u1))) / area;
  real s22 = int2d(Th)(lam*(e11+e22+dx(u1)+dy(u2)) + 2*mu*(e22+dy(u2))) / area;
  real s12 = int2d(Th)(mu*(g12+dy(u1)+dx(u2))) / area;
  cout << "LIMSURF_C " << j << " " << s11 << " " << s22 << " " << s12 << endl;
}
)";
    return s.str();
}

/// Writes and runs the script; fails the test (and returns zeros) when FreeFem++ does not finish.
PeerResult run_freefem(const fs::path& freefem, const std::vector<InterfaceLoop>& loops, int side, int stride,
                       const char* tag) {
    const fs::path dir = test::make_temp_dir(tag);
    const fs::path script = dir / "cell.edp";
    const fs::path log = dir / "cell.log";
    std::ofstream(script) << freefem_script(loops, side, stride);
    const std::string cmd =
        "\"" + freefem.string() + "\" -nw -ne \"" + script.string() + "\" > \"" + log.string() + "\" 2>&1";
    const auto t0 = std::chrono::steady_clock::now();
    const int rc = std::system(cmd.c_str());
    PeerResult r;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(rc, 0) << cmd;
    std::ifstream in(log);
    int columns = 0;
    bool areas = false;
    for (std::string line; std::getline(in, line);) {
        std::istringstream words(line);
        std::string word;
        words >> word;
        if (word == "LIMSURF_AREA") {
            areas = static_cast<bool>(words >> r.area >> r.inclusion_area >> r.triangles);
        } else if (word == "LIMSURF_C") {
            int j = -1;
            words >> j >> r.C(0, j) >> r.C(1, j) >> r.C(2, j);
            columns += words && j == columns ? 1 : 0;
        }
    }
    EXPECT_TRUE(areas && columns == 3) << "FreeFem++ output not understood, see " << log;
    if (rc == 0 && areas && columns == 3) {
        fs::remove_all(dir);  // kept for a look when FreeFem++ failed
    }
    return r;
}

double relative(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
    return (a - b).norm() / b.norm();
}

/// Material 1 for the faces of @p group, 0 for the others.
std::vector<Index> two_materials(const BuildResult& built, const char* group) {
    const Index second = built.groups.find(group);
    EXPECT_GE(second, 0) << "no face group " << group;
    std::vector<Index> material(static_cast<std::size_t>(built.mesh.topology().num_faces()));
    for (Index f = 0; f < built.mesh.topology().num_faces(); ++f) {
        material[f] = built.groups.group_of(f) == second ? 1 : 0;
    }
    return material;
}

/// limsurf's periodic cell with the peer's materials on levels 0..levels.
ElasticityStudy limsurf_levels(const BuildResult& built, const std::vector<Index>& material, int levels) {
    ElasticityStudyOptions options;
    options.body.materials = {kMatrix, kInclusion};
    options.body.face_material = material;
    options.body.model = PlaneModel::Strain;
    options.boundary = ElasticBoundary::Periodic;
    options.effective_stiffness = true;
    options.levels = levels;
    return solve_elasticity_levels(built.mesh.topology(), built.mesh.positions(), options);
}

double total_area(const std::vector<InterfaceLoop>& loops) {
    double a = 0.0;
    for (const InterfaceLoop& loop : loops) {
        a += polygon_area(loop.points);
    }
    return a;
}

TEST(ElasticityFreeFemPeer, HomogeneousCellGivesTheMaterialExactly) {
    const fs::path freefem = find_freefem();
    if (freefem.empty()) {
        GTEST_SKIP() << "FreeFem++ not installed (apt install freefem++)";
    }
    // No interface: the fluctuation is zero and C* is the matrix's plane-strain C (the script's own
    // constitutive law, Voigt convention and averaging, against the library's elasticity_matrix).
    const PeerResult r = run_freefem(freefem, {}, 16, 1, "elasticity_freefem_homogeneous");
    EXPECT_NEAR(r.area, 1.0, 1e-12);
    EXPECT_EQ(r.inclusion_area, 0.0);
    EXPECT_LT(relative(r.C, elasticity_matrix(kMatrix, PlaneModel::Strain)), 1e-9) << r.C;
}

TEST(ElasticityFreeFemPeer, SquareInclusionEffectiveStiffnessMatchesFreeFem) {
    const fs::path freefem = find_freefem();
    if (freefem.empty()) {
        GTEST_SKIP() << "FreeFem++ not installed (apt install freefem++)";
    }
    const BuildResult built = read_mesh(test::find_bundled("square_inclusion").path);
    const Topology& topo = built.mesh.topology();
    const Points& X = built.mesh.positions();
    const std::vector<Index> material = two_materials(built, "inclusion");

    const LimitBasis basis(topo, SchemeKind::CatmullClark);
    const std::vector<InterfaceLoop> loops = interface_loops(basis, X, material);
    ASSERT_EQ(loops.size(), 1u);
    ASSERT_EQ(loops[0].points.size(), 24u * kPerEdge);  // the 24 creased interface edges
    const double polygon = polygon_area(loops[0].points);
    // The limit interface passes through radius 0.25 at its vertices and bulges by less than 1 % between.
    for (const auto& p : loops[0].points) {
        EXPECT_NEAR((p - Eigen::Vector2d(0.5, 0.5)).norm(), 0.25, 0.0025);
    }

    // The peer at two resolutions (a mesh edge every 16 and every 8 interface samples): its error is
    // the chords' (their area deficit goes like h², P2's error in C* is far smaller), so the fine
    // run's is about a third of their difference (measured 1.5e-4): far below the tolerance.
    const PeerResult coarse = run_freefem(freefem, loops, 16, 16, "elasticity_freefem_coarse");
    const PeerResult peer = run_freefem(freefem, loops, 32, 8, "elasticity_freefem_fine");
    std::printf("FreeFem++ C* (%d triangles, %.1f s):\n", peer.triangles, peer.seconds);
    std::printf("  %.8f %.8f %.8f\n  %.8f %.8f %.8f\n  %.8f %.8f %.8f\n", peer.C(0, 0), peer.C(0, 1), peer.C(0, 2),
                peer.C(1, 0), peer.C(1, 1), peer.C(1, 2), peer.C(2, 0), peer.C(2, 1), peer.C(2, 2));
    std::printf("FreeFem++ coarse (%d triangles) against fine: %.2e; inclusion area %.8f (polygon %.8f)\n",
                coarse.triangles, relative(coarse.C, peer.C), peer.inclusion_area, polygon);
    EXPECT_LT(relative(coarse.C, peer.C), 3e-4);
    // Richardson on the chords' h² (the stride halves): the peer with its geometric error removed.
    const Eigen::Matrix3d extrapolated = peer.C + (peer.C - coarse.C) / 3.0;
    std::printf("FreeFem++ extrapolated: C11 %.8f C12 %.8f C33 %.8f\n", extrapolated(0, 0), extrapolated(0, 1),
                extrapolated(2, 2));
    EXPECT_NEAR(peer.area, 1.0, 1e-10);
    // FreeFem's mesh edges are chords of 8 samples: they lose about π (8h)² / 6 ≈ 3.5e-5 of the area.
    EXPECT_NEAR(peer.inclusion_area, polygon, 5e-5);

    const ElasticityStudy study = limsurf_levels(built, material, 2);
    ASSERT_EQ(study.levels.size(), 3u);
    std::vector<double> differences;
    for (const ElasticityLevel& level : study.levels) {
        ASSERT_TRUE(level.effective_stiffness.has_value());
        const Eigen::Matrix3d& C = *level.effective_stiffness;
        const auto& a = level.averages.material_area;
        ASSERT_EQ(a.size(), 2u);
        std::printf("level %d (%td vertices, %.1f s): C11 %.6f C12 %.6f C33 %.6f, relative difference %.2e "
                    "(extrapolated peer %.2e), inclusion area %.8f\n",
                    level.level, static_cast<std::ptrdiff_t>(level.X.rows()), level.seconds, C(0, 0), C(0, 1), C(2, 2),
                    relative(C, peer.C), relative(C, extrapolated), a[1]);
        differences.push_back(relative(C, extrapolated));
        // The same limit geometry: the quadrature's areas against the polygon of the limit interface
        // (its chords of length h lose about π h² / 6 ≈ 5e-7 of the area) and the unit square.
        EXPECT_NEAR(a[1], polygon, 2e-6) << "level " << level.level;
        EXPECT_NEAR(a[0] + a[1], 1.0, 1e-10) << "level " << level.level;
    }
    const Eigen::Matrix3d& finest = *study.levels.back().effective_stiffness;
    EXPECT_LT(relative(finest, peer.C), 1e-3) << "limsurf\n" << finest << "\nFreeFem++\n" << peer.C;
    // Closer with each level (measured against the extrapolated peer: 6.1e-4, 8.8e-5, 1.3e-5).
    EXPECT_LT(differences[1], differences[0]);
    EXPECT_LT(differences[2], differences[1]);
    EXPECT_LT(differences[2], 5e-5);
}

TEST(ElasticityFreeFemPeer, RveBlockApproachesFreeFemAtFirstOrder) {
    const fs::path freefem = find_freefem();
    if (freefem.empty()) {
        GTEST_SKIP() << "FreeFem++ not installed (apt install freefem++)";
    }
    // No crease at the grains' boundaries: the basis is C² across the jump in stiffness, where the
    // exact strain jumps, so C* converges only at first order in h (studies/elasticity_rve.py: rate ≈ 1).
    // Measured against FreeFem: 13.9 %, 6.2 %, 3.1 % on levels 0..2.
    const BuildResult built = read_mesh(test::find_bundled("rve_block").path);
    const std::vector<Index> material = two_materials(built, "grain");
    const LimitBasis basis(built.mesh.topology(), SchemeKind::CatmullClark);
    const std::vector<InterfaceLoop> loops = interface_loops(basis, built.mesh.positions(), material);
    ASSERT_EQ(loops.size(), 4u);  // four grains, each around one vertex
    const PeerResult peer = run_freefem(freefem, loops, 32, 8, "elasticity_freefem_rve");
    EXPECT_NEAR(peer.inclusion_area, total_area(loops), 2e-4);  // FreeFem's chords: 8e-5 measured
    std::printf("FreeFem++ C* of rve_block: C11 %.8f C12 %.8f C22 %.8f C13 %.2e C23 %.2e C33 %.8f\n", peer.C(0, 0),
                peer.C(0, 1), peer.C(1, 1), peer.C(0, 2), peer.C(1, 2), peer.C(2, 2));
    const ElasticityStudy study = limsurf_levels(built, material, 2);
    std::vector<double> differences;
    for (const ElasticityLevel& level : study.levels) {
        ASSERT_TRUE(level.effective_stiffness.has_value());
        differences.push_back(relative(*level.effective_stiffness, peer.C));
        std::printf("rve_block level %d: relative difference to FreeFem++ (%d triangles) %.2e, grain area %.8f "
                    "(polygon %.8f, FreeFem %.8f)\n",
                    level.level, peer.triangles, differences.back(), level.averages.material_area[1], total_area(loops),
                    peer.inclusion_area);
        EXPECT_NEAR(level.averages.material_area[1], total_area(loops), 1e-5);
    }
    // Halved (give or take) with each level, from above.
    EXPECT_LT(differences[1], 0.6 * differences[0]);
    EXPECT_LT(differences[2], 0.6 * differences[1]);
    EXPECT_LT(differences[2], 0.05);
    EXPECT_GT((*study.levels.back().effective_stiffness)(0, 0), peer.C(0, 0));
}

}  // namespace
}  // namespace limsurf
