// limsurf eigen --scheme S --valence N [--boundary] [--weights A,B,G] [--rings R]
//   [--characteristic-map OUT] [--json]: the spectrum of the local subdivision matrix around one
// extraordinary vertex (Fourier block by block), the subdominant eigenvalue, the characteristic
// map and the classical smoothness verdicts (docs/eigen.md).
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/limit_options.h"
#include "limsurf/analysis/eigen_analysis.h"
#include "limsurf/io/mesh_io.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct EigenOptions {
    std::string scheme;
    int valence = 0;
    bool boundary = false;
    std::string weights;
    int rings = 0;
    std::string map_output;
    bool json = false;
};

const std::map<std::string, SchemeKind>& eigen_schemes() {
    static const std::map<std::string, SchemeKind> names{{"catmull-clark", SchemeKind::CatmullClark},
                                                         {"loop", SchemeKind::Loop},
                                                         {"doo-sabin", SchemeKind::DooSabin},
                                                         {"c2g0", SchemeKind::C2g0}};
    return names;
}

/// "ALPHA,BETA,GAMMA" (the paper's own weights of the vertex; docs/schemes.md).
VertexRuleWeights parse_weights(const std::string& text) {
    std::istringstream in(text);
    VertexRuleWeights w;
    char c1 = 0, c2 = 0;
    std::string rest;
    LIMSURF_CHECK((in >> w.alpha >> c1 >> w.beta >> c2 >> w.gamma) && c1 == ',' && c2 == ',' && !(in >> rest),
                  InputError, "--weights: expected ALPHA,BETA,GAMMA (e.g. 13.4575,0.999938,0.999938), got '", text,
                  "'");
    LIMSURF_CHECK(std::isfinite(w.alpha) && std::isfinite(w.beta) && std::isfinite(w.gamma) && w.alpha > 0.0 &&
                      w.beta >= 0.0 && w.gamma >= 0.0,
                  InputError, "--weights: alpha must be > 0 and beta, gamma >= 0, all finite, got '", text, "'");
    return w;
}

nlohmann::json complex_json(std::complex<double> z) {
    return {{"re", z.real()}, {"im", z.imag()}, {"abs", std::abs(z)}};
}

nlohmann::json test_json(const SmoothnessTest& t) {
    return {{"checked", t.checked},
            {"passed", t.checked ? nlohmann::json(t.passed) : nlohmann::json(nullptr)},
            {"detail", t.detail}};
}

nlohmann::json spectrum_json(const SchemeSpectrum& s, const EigenOptions& options) {
    nlohmann::json values = nlohmann::json::array();
    for (const EigenvalueEntry& e : s.eigenvalues) {
        values.push_back({{"value", complex_json(e.value)},
                          {"frequency", e.frequency < 0 ? nlohmann::json(nullptr) : nlohmann::json(e.frequency)},
                          {"algebraic", e.algebraic},
                          {"geometric", e.geometric},
                          {"jordan_blocks", e.jordan_blocks}});
    }
    const CharacteristicMap& m = s.characteristic_map;
    nlohmann::json map{{"evaluated", m.evaluated}};
    if (m.evaluated) {
        map["min_jacobian"] = m.min_jacobian;
        map["max_jacobian"] = m.max_jacobian;
        map["winding_number"] = m.winding_number;
        map["samples"] = m.samples;
    } else {
        map["reason"] = m.reason;
    }
    return {{"scheme", options.scheme},
            {"valence", options.valence},
            {"boundary", options.boundary},
            {"rings", s.rings},
            {"size", s.S.rows()},
            {"symmetry_residual", s.symmetry_residual},
            {"dominant", s.dominant},
            {"subdominant", s.subdominant},
            {"subdominant_multiplicity", s.subdominant_multiplicity},
            {"subsubdominant", s.subsubdominant},
            {"subsubdominant_multiplicity", s.subsubdominant_multiplicity},
            {"eigenvalues", values},
            {"characteristic_map", map},
            {"tests",
             {{"c1_spectrum", test_json(s.c1_spectrum)},
              {"c1", test_json(s.c1)},
              {"bounded_curvature", test_json(s.bounded_curvature)},
              {"c2_necessary", test_json(s.c2_necessary)}}}};
}

void print_text(const SchemeSpectrum& s, const EigenOptions& options) {
    std::cout << options.scheme << ", " << (options.boundary ? "boundary " : "") << "valence " << options.valence
              << ": " << s.S.rows() << "x" << s.S.rows() << " local subdivision matrix (" << s.rings << " rings)\n";
    std::cout << std::setprecision(12) << "subdominant  " << s.subdominant << " (x" << s.subdominant_multiplicity
              << "), next " << s.subsubdominant << " (x" << s.subsubdominant_multiplicity << "), lambda^2 "
              << s.subdominant * s.subdominant << "\n";
    std::cout << "eigenvalue                      |value|       frequency  alg  geo  jordan\n";
    for (const EigenvalueEntry& e : s.eigenvalues) {
        std::ostringstream value;
        value << std::setprecision(10) << e.value.real();
        if (std::abs(e.value.imag()) > 1e-12) {
            value << (e.value.imag() < 0 ? " - " : " + ") << std::abs(e.value.imag()) << "i";
        }
        std::ostringstream blocks;
        for (std::size_t i = 0; i < e.jordan_blocks.size(); ++i) {
            blocks << (i ? "+" : "") << e.jordan_blocks[i];
        }
        std::cout << std::left << std::setw(32) << value.str() << std::setw(14) << std::setprecision(6)
                  << std::abs(e.value) << std::right << std::setw(9)
                  << (e.frequency < 0 ? std::string("-") : std::to_string(e.frequency)) << std::setw(5) << e.algebraic
                  << std::setw(5) << e.geometric << "  " << blocks.str() << "\n";
    }
    const auto verdict = [](const char* name, const SmoothnessTest& t) {
        std::cout << std::left << std::setw(20) << name << std::right
                  << (t.checked ? (t.passed ? "yes" : "NO") : "not checked") << "  (" << t.detail << ")\n";
    };
    verdict("C1 (spectrum)", s.c1_spectrum);
    verdict("C1 (Reif)", s.c1);
    verdict("bounded curvature", s.bounded_curvature);
    verdict("C2 necessary (17)", s.c2_necessary);
}

int run_eigen(const EigenOptions& options) {
    EigenRequest request;
    request.scheme = eigen_schemes().at(options.scheme);
    request.valence = options.valence;
    request.boundary = options.boundary;
    request.rings = options.rings;
    if (!options.weights.empty()) {
        request.weights = parse_weights(options.weights);
    }
    const SchemeSpectrum s = analyse_scheme(request);
    if (!options.map_output.empty()) {
        const CharacteristicMap& m = s.characteristic_map;
        LIMSURF_CHECK(m.evaluated, UnsupportedError, options.map_output,
                      ": no characteristic map to write: ", m.reason);
        const ControlMesh mesh(Topology::from_polygons(m.positions.rows(), m.faces), m.positions);
        print_warnings(write_mesh(options.map_output, mesh));
    }
    if (options.json) {
        print_json(spectrum_json(s, options));
    } else {
        require_finite(spectrum_json(s, options));
        print_text(s, options);
    }
    return exit_ok;
}

}  // namespace

void add_eigen_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<EigenOptions>();
    CLI::App* cmd = app.add_subcommand(
        "eigen", "Spectrum of a scheme's local subdivision matrix at one extraordinary vertex, and its smoothness");
    cmd->add_option("--scheme", options->scheme, "Subdivision scheme")
        ->required()
        ->check(CLI::IsMember(names_of(eigen_schemes())));
    cmd->add_option("--valence", options->valence,
                    "Valence of the vertex (edges at it; Doo-Sabin: corners of the extraordinary face)")
        ->required();
    cmd->add_flag("--boundary", options->boundary, "The vertex on a boundary (catmull-clark, loop): valence - 1 faces");
    cmd->add_option("--weights", options->weights,
                    "Tuned catmull-clark weights ALPHA,BETA,GAMMA of the vertex (the paper's Fig. 1 reading)");
    cmd->add_option("--rings", options->rings, "Rings of the neighbourhood (default: what the scheme needs)");
    cmd->add_option("--characteristic-map", options->map_output,
                    "Write the sampled characteristic map as a mesh (.obj, .off, .ply)");
    cmd->add_flag("--json", options->json, "Print JSON");
    cmd->callback([options, &status] { status.exit_code = run_guarded([&] { return run_eigen(*options); }); });
}

}  // namespace limsurf::cli
