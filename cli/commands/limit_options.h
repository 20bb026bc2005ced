// Options shared by the commands that evaluate the limit surface (eval, measure, volume):
// the scheme and its rules, taken from the command line, else the file's hints.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "limsurf/apps/laplacian_method.h"
#include "limsurf/core/error.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/mesh/control_mesh.h"

namespace limsurf::cli {

struct LimitSchemeOptions {
    std::string scheme;
    std::string boundary;   // empty: the file's hint, else edge-and-corner
    std::string creasing;   // empty: the file's hint, else uniform
    std::string triangles;  // empty: the file's hint, else catmull-clark
};

inline const std::map<std::string, SchemeKind>& limit_schemes() {
    static const std::map<std::string, SchemeKind> names{{"catmull-clark", SchemeKind::CatmullClark},
                                                         {"loop", SchemeKind::Loop},
                                                         {"doo-sabin", SchemeKind::DooSabin},
                                                         {"c2g0", SchemeKind::C2g0}};
    return names;
}
inline const std::map<std::string, BoundaryInterpolation>& boundary_names() {
    static const std::map<std::string, BoundaryInterpolation> names{
        {"none", BoundaryInterpolation::None},
        {"edge-only", BoundaryInterpolation::EdgeOnly},
        {"edge-and-corner", BoundaryInterpolation::EdgeAndCorner}};
    return names;
}
inline const std::map<std::string, CreasingMethod>& creasing_names() {
    static const std::map<std::string, CreasingMethod> names{{"uniform", CreasingMethod::Uniform},
                                                             {"chaikin", CreasingMethod::Chaikin}};
    return names;
}
inline const std::map<std::string, TriangleSubdivision>& triangle_names() {
    static const std::map<std::string, TriangleSubdivision> names{{"catmull-clark", TriangleSubdivision::CatmullClark},
                                                                  {"smooth", TriangleSubdivision::Smooth}};
    return names;
}

template <class T>
std::vector<std::string> names_of(const std::map<std::string, T>& names) {
    std::vector<std::string> out;
    for (const auto& [name, value] : names) {
        out.push_back(name);
    }
    return out;
}

/// Registers --scheme (required), --boundary, --creasing, --triangles on @p cmd.
inline void add_limit_scheme_options(CLI::App* cmd, LimitSchemeOptions& options) {
    cmd->add_option("--scheme", options.scheme, "Subdivision scheme of the limit surface")
        ->required()
        ->check(CLI::IsMember(names_of(limit_schemes())));
    cmd->add_option("--boundary", options.boundary,
                    "Boundary rule (default: the file's interpolateboundary tag, else edge-and-corner)")
        ->check(CLI::IsMember(names_of(boundary_names())));
    cmd->add_option("--creasing", options.creasing, "Semi-sharp crease decay (default: the file's tag, else uniform)")
        ->check(CLI::IsMember(names_of(creasing_names())));
    cmd->add_option("--triangles", options.triangles,
                    "Catmull-Clark rule for triangles (default: the file's tag, else catmull-clark)")
        ->check(CLI::IsMember(names_of(triangle_names())));
}

template <class T>
T choose_rule(const std::string& flag, const std::map<std::string, T>& names, const std::optional<T>& hint,
              T fallback) {
    return flag.empty() ? hint.value_or(fallback) : names.at(flag);
}

/// --method dec|decsnap|sec|secsnap and --level L (0..8): the inner products of the SEC
/// applications (sec/inner_products.h), the same words and range in every command.
inline void add_inner_product_options(CLI::App* cmd, std::string& method, int& level) {
    cmd->add_option("--method", method, "Inner products: dec, decsnap, sec, secsnap (default sec)")
        ->check(CLI::IsMember({"dec", "decsnap", "sec", "secsnap"}));
    cmd->add_option("--level", level, "Subdivision level L of sec and secsnap (0..8, default 3)")
        ->check(CLI::Range(0, 8));
}

/// --method dec|decsnap|sec|secsnap|iga and --level L (0..8): how an application discretises the
/// Laplacian (apps/laplacian_method.h), the same words and range in every command that takes iga.
inline void add_laplacian_method_options(CLI::App* cmd, std::string& method, int& level) {
    cmd->add_option("--method", method,
                    "dec, decsnap, sec, secsnap (inner products, default sec) or iga (Galerkin with the limit basis)")
        ->check(CLI::IsMember({"dec", "decsnap", "sec", "secsnap", "iga"}));
    cmd->add_option("--level", level, "Subdivision level L of sec and secsnap (0..8, default 3)")
        ->check(CLI::Range(0, 8));
}

/// --degree D (1..60) and --tiles T (0..20): iga's quadrature of the limit surface (SamplerOptions).
inline void add_iga_quadrature_options(CLI::App* cmd, int& degree, int& tiles) {
    cmd->add_option("--degree", degree, "iga: quadrature degree per tile (1..60, default 8)")->check(CLI::Range(1, 60));
    cmd->add_option("--tiles", tiles, "iga: tile levels towards extraordinary vertices (0..20, default 6)")
        ->check(CLI::Range(0, 20));
}

/// @brief Refuses --level without --method sec or secsnap when given: the method would ignore it
///   without a word (as --lumped with iga is refused).
/// @throws InputError naming the option and the method
inline void check_level_option(const CLI::App& cmd, const std::string& method) {
    LIMSURF_CHECK(has_level(parse_laplacian_method(method)) || cmd.count("--level") == 0, InputError,
                  "--level applies to --method sec and secsnap, not to ", method);
}

/// @brief check_level_option(), and refuses add_iga_quadrature_options()' --degree and --tiles
///   without --method iga.
/// @throws InputError naming the option and the method
inline void check_method_options(const CLI::App& cmd, const std::string& method) {
    check_level_option(cmd, method);
    for (const char* name : {"--degree", "--tiles"}) {
        LIMSURF_CHECK(parse_laplacian_method(method) == LaplacianMethod::Iga || cmd.count(name) == 0, InputError,
                      name, " applies to --method iga, not to ", method);
    }
}

/// The rules chosen on the command line, else the file's hints, else the defaults.
inline SchemeOptions scheme_rules(const ControlMesh& mesh, const LimitSchemeOptions& options) {
    const SchemeHints& hints = mesh.hints();
    const SchemeOptions defaults;
    SchemeOptions rules;
    rules.boundary = choose_rule(options.boundary, boundary_names(), hints.boundary, defaults.boundary);
    rules.creasing = choose_rule(options.creasing, creasing_names(), hints.creasing, defaults.creasing);
    rules.triangles = choose_rule(options.triangles, triangle_names(), hints.triangles, defaults.triangles);
    return rules;
}

/// The limit basis of @p mesh under the chosen scheme and rules.
inline LimitBasis make_limit_basis(const ControlMesh& mesh, const LimitSchemeOptions& options) {
    return LimitBasis(mesh.topology(), limit_schemes().at(options.scheme), scheme_rules(mesh, options));
}

}  // namespace limsurf::cli
