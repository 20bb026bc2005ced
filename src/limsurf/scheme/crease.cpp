#include "limsurf/scheme/crease.h"

#include <cstddef>

namespace limsurf {

double decrement_sharpness(double sharpness) noexcept {
    if (is_smooth_sharpness(sharpness)) {
        return 0.0;
    }
    if (is_infinitely_sharp(sharpness)) {
        return infinite_sharpness;
    }
    return sharpness > 1.0 ? sharpness - 1.0 : 0.0;
}

CreaseRule vertex_rule(double vertex_sharpness, int sharp_edge_count) noexcept {
    if (is_sharp(vertex_sharpness) || sharp_edge_count > 2) {
        return CreaseRule::Corner;
    }
    if (sharp_edge_count == 2) {
        return CreaseRule::Crease;
    }
    return sharp_edge_count == 1 ? CreaseRule::Dart : CreaseRule::Smooth;
}

CreaseRule vertex_rule(double vertex_sharpness, std::span<const double> edge_sharpness) noexcept {
    int count = 0;
    for (const double s : edge_sharpness) {
        count += is_sharp(s) ? 1 : 0;
    }
    return vertex_rule(vertex_sharpness, count);
}

double subdivide_edge_sharpness_at_vertex(double edge_sharpness, std::span<const double> sharpness_at_vertex,
                                          CreasingMethod method) noexcept {
    if (method == CreasingMethod::Uniform || sharpness_at_vertex.size() < 2) {
        return decrement_sharpness(edge_sharpness);
    }
    if (is_smooth_sharpness(edge_sharpness)) {
        return 0.0;
    }
    if (is_infinitely_sharp(edge_sharpness)) {
        return infinite_sharpness;
    }
    double sum = 0.0;
    int count = 0;
    for (const double s : sharpness_at_vertex) {
        if (is_semi_sharp(s)) {
            sum += s;
            ++count;
        }
    }
    double s = edge_sharpness;
    if (count > 1) {
        // Chaikin: blend with the mean of the other semi-sharp edges at this end.
        const double others = (sum - edge_sharpness) / static_cast<double>(count - 1);
        s = 0.75 * edge_sharpness + 0.25 * others;
    }
    s -= 1.0;
    return is_sharp(s) ? s : 0.0;
}

void subdivide_edge_sharpness_around_vertex(std::span<const double> parent, std::span<double> child,
                                            CreasingMethod method) noexcept {
    for (std::size_t i = 0; i < parent.size(); ++i) {
        child[i] = subdivide_edge_sharpness_at_vertex(parent[i], parent, method);
    }
}

double fractional_weight_at_vertex(double parent_vertex_sharpness, double child_vertex_sharpness,
                                   std::span<const double> parent_edges, std::span<const double> child_edges,
                                   CreasingMethod method) noexcept {
    int count = 0;
    double sum = 0.0;
    if (is_sharp(parent_vertex_sharpness) && is_smooth_sharpness(child_vertex_sharpness)) {
        count = 1;
        sum = parent_vertex_sharpness;
    }
    for (std::size_t i = 0; i < parent_edges.size(); ++i) {
        const double p = parent_edges[i];
        // Uniform: an edge becomes smooth exactly when its sharpness is at most 1.
        const bool decays = method == CreasingMethod::Uniform ? (is_sharp(p) && p <= 1.0)
                                                              : (is_sharp(p) && is_smooth_sharpness(child_edges[i]));
        if (decays) {
            sum += p;
            ++count;
        }
    }
    if (count == 0) {
        return 0.0;
    }
    const double weight = sum / static_cast<double>(count);
    return weight > 1.0 ? 1.0 : weight;
}

std::array<int, 2> crease_ends(std::span<const double> edge_sharpness) noexcept {
    int first = 0;
    while (is_smooth_sharpness(edge_sharpness[static_cast<std::size_t>(first)])) {
        ++first;
    }
    int last = static_cast<int>(edge_sharpness.size()) - 1;
    while (is_smooth_sharpness(edge_sharpness[static_cast<std::size_t>(last)])) {
        --last;
    }
    return {first, last};
}

}  // namespace limsurf
