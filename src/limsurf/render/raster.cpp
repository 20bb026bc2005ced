#include "raster.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace limsurf::detail {
namespace {

/// The edge function of (p, q) at s, twice the signed area of (p, q, s), evaluated from the
/// lexicographically smaller endpoint so that the two triangles sharing an edge compute exactly
/// opposite values (no sample slips between them by rounding). @p flipped tells whether (p, q) was
/// swapped to get there.
struct Edge {
    Eigen::Vector2d from;
    Eigen::Vector2d delta;
    double sign = 1.0;
};

Edge make_edge(const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
    const bool swap = q.x() < p.x() || (q.x() == p.x() && q.y() < p.y());
    const Eigen::Vector3d& from = swap ? q : p;
    const Eigen::Vector3d& to = swap ? p : q;
    return {from.head<2>(), (to - from).head<2>(), swap ? -1.0 : 1.0};
}

double edge_value(const Edge& e, double x, double y) {
    return e.delta.x() * (y - e.from.y()) - e.delta.y() * (x - e.from.x());
}

}  // namespace

SampleBuffer::SampleBuffer(int w, int h)
    : width(w), height(h), depth(at(0, h), -std::numeric_limits<double>::infinity()), triangle(at(0, h), invalid_index),
      b1(at(0, h), 0.0f), b2(at(0, h), 0.0f), line(at(0, h), 0) {}

void draw_triangle(SampleBuffer& buffer, Index id, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                   const Eigen::Vector3d& c) {
    const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    if (area == 0.0 || !std::isfinite(area)) {
        return;  // seen edge-on: covers no sample
    }
    const double orientation = area > 0.0 ? 1.0 : -1.0;
    // Edge k is opposite corner k; its function, oriented so that the inside is positive, is the
    // barycentric weight of corner k times |area|.
    const Edge edges[3] = {make_edge(b, c), make_edge(c, a), make_edge(a, b)};
    const double scale[3] = {orientation * edges[0].sign, orientation * edges[1].sign, orientation * edges[2].sign};
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}) - 0.5)));
    const int x1 = std::min(buffer.width - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}) - 0.5)));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}) - 0.5)));
    const int y1 = std::min(buffer.height - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}) - 0.5)));
    const double inverse_area = 1.0 / std::abs(area);
    for (int y = y0; y <= y1; ++y) {
        const double sy = y + 0.5;
        for (int x = x0; x <= x1; ++x) {
            const double sx = x + 0.5;
            double w[3];
            bool inside = true;
            for (int k = 0; k < 3 && inside; ++k) {
                w[k] = scale[k] * edge_value(edges[k], sx, sy);
                // On a shared edge the sample goes to the triangle on the edge's canonical left.
                inside = w[k] > 0.0 || (w[k] == 0.0 && scale[k] > 0.0);
            }
            if (!inside) {
                continue;
            }
            const double l1 = w[1] * inverse_area;
            const double l2 = w[2] * inverse_area;
            const double z = (1.0 - l1 - l2) * a.z() + l1 * b.z() + l2 * c.z();
            const std::size_t s = buffer.at(x, y);
            if (z > buffer.depth[s]) {
                buffer.depth[s] = z;
                buffer.triangle[s] = id;
                buffer.b1[s] = static_cast<float>(l1);
                buffer.b2[s] = static_cast<float>(l2);
            }
        }
    }
}

void draw_line(SampleBuffer& buffer, const Eigen::Vector3d& a, const Eigen::Vector3d& b, int width, double bias) {
    const double length = std::max(std::abs(b.x() - a.x()), std::abs(b.y() - a.y()));
    if (!std::isfinite(length)) {
        return;
    }
    const int steps = static_cast<int>(std::ceil(length)) + 1;
    for (int k = 0; k <= steps; ++k) {
        const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(k) / steps);
        const int x0 = static_cast<int>(std::floor(p.x() - 0.5 * width));
        const int y0 = static_cast<int>(std::floor(p.y() - 0.5 * width));
        for (int y = std::max(0, y0); y < std::min(buffer.height, y0 + width); ++y) {
            for (int x = std::max(0, x0); x < std::min(buffer.width, x0 + width); ++x) {
                const std::size_t s = buffer.at(x, y);
                if (p.z() + bias >= buffer.depth[s]) {
                    buffer.line[s] = 1;
                }
            }
        }
    }
}

}  // namespace limsurf::detail
