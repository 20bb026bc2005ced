#include "limsurf/scheme/tuned_weights.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "limsurf/core/error.h"
#include "limsurf/core/input_file.h"

namespace limsurf {
namespace {

void check_weights(const VertexRuleWeights& w, const std::string& what) {
    LIMSURF_CHECK(std::isfinite(w.alpha) && std::isfinite(w.beta) && std::isfinite(w.gamma), InputError, what,
                  ": weights must be finite");
    LIMSURF_CHECK(w.alpha > 0.0, InputError, what, ": alpha must be > 0, got ", w.alpha);
    LIMSURF_CHECK(w.beta >= 0.0 && w.gamma >= 0.0, InputError, what, ": beta and gamma must be >= 0");
}

}  // namespace

VertexRuleWeights catmull_clark_weights(int valence) noexcept {
    return {static_cast<double>(valence) * (valence - 2), 1.0, 1.0};
}

TunedWeights TunedWeights::preset(std::string_view name) {
    TunedWeights weights;
    if (name == "cup") {
        weights.set_valence(5, {13.4575, 0.999938, 0.999938});
    } else if (name == "saddle") {
        weights.set_valence(5, {13.9851, 0.824885, 0.824885});
    } else if (name != "catmull-clark") {
        throw InputError(detail::concat("unknown weight preset '", name, "' (expected cup, saddle or catmull-clark)"));
    }
    return weights;
}

TunedWeights TunedWeights::from_file(const std::filesystem::path& path) {
    std::ifstream in = open_input_file(path);
    TunedWeights weights;
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        line = line.substr(0, line.find('#'));
        std::istringstream fields(line);
        std::string first;
        if (!(fields >> first)) {
            continue;
        }
        const std::string where = detail::concat(path.string(), ":", number);
        VertexRuleWeights w;
        std::string rest;
        try {
            if (first == "vertex") {
                long long vertex = -1;
                LIMSURF_CHECK((fields >> vertex >> w.alpha >> w.beta >> w.gamma) && !(fields >> rest) && vertex >= 0 &&
                                  vertex <= 2147483647LL,
                              InputError, "expected 'vertex INDEX alpha beta gamma'");
                weights.set_vertex(static_cast<Index>(vertex), w);
            } else {
                std::size_t used = 0;
                const int valence = std::stoi(first, &used);
                LIMSURF_CHECK(used == first.size() && (fields >> w.alpha >> w.beta >> w.gamma) && !(fields >> rest),
                              InputError, "expected 'valence alpha beta gamma'");
                weights.set_valence(valence, w);
            }
        } catch (const InputError& error) {
            throw InputError(where + ": " + error.what());
        } catch (const std::exception&) {
            throw InputError(where + ": expected 'valence alpha beta gamma' or 'vertex INDEX alpha beta gamma'");
        }
    }
    return weights;
}

void TunedWeights::set_valence(int valence, VertexRuleWeights weights) {
    LIMSURF_CHECK(valence >= 3, InputError, "valence ", valence, ": tuned weights need a valence >= 3");
    check_weights(weights, detail::concat("valence ", valence));
    by_valence_[valence] = weights;
}

void TunedWeights::set_vertex(Index vertex, VertexRuleWeights weights) {
    LIMSURF_CHECK(vertex >= 0, InputError, "vertex ", vertex, ": index must be >= 0");
    check_weights(weights, detail::concat("vertex ", vertex));
    by_vertex_[vertex] = weights;
}

VertexRuleWeights TunedWeights::at(Index vertex, int valence) const {
    if (const auto it = by_vertex_.find(vertex); it != by_vertex_.end()) {
        return it->second;
    }
    if (const auto it = by_valence_.find(valence); it != by_valence_.end()) {
        return it->second;
    }
    return catmull_clark_weights(valence);
}

}  // namespace limsurf
