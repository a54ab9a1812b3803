// A face's check (face_check.hpp).
#include "refine/face_check.hpp"

#include "erase/erase_cost.hpp"
#include "erase/lattice_scan.hpp"
#include "erase/swallowed.hpp"
#include "refine/motion_bounds.hpp"

#include <algorithm>
#include <cmath>

namespace tinlod::refine {

using namespace erase;

namespace {

// Puts the nodes of face f's list (`deviation(u)` gives node u's) in runs by the square of a grid
// over the face's box in xy that holds them, and keeps each run as a block: its first node, its
// length, its nodes' largest deviation and their box. A scan then skips a block whose deviation
// times the largest weight in its box cannot matter: a face of ~10^5 nodes on a flat, in sight of
// a low eye, was weighed node by node every frame (docs/decisions/010-large-faces.md).
template <class Deviation>
static void build_blocks(EraserState &s, FaceBlocks &fb, FH f, const glm::dvec2 &lo,
                         const glm::dvec2 &hi, const Deviation &deviation) {
    std::vector<std::int32_t> &nodes = fb.block_scratch;
    nodes.clear();
    for (std::int32_t u = s.faces.face_head[f.idx()]; u >= 0; u = s.faces.next_swallowed[u])
        nodes.push_back(u);
    constexpr int cells = k_block_side * k_block_side;
    std::array<std::uint32_t, cells + 1> start{};
    std::vector<std::uint8_t> &cell_of_node = fb.block_cell_scratch;
    cell_of_node.resize(nodes.size());
    const glm::dvec2 scale = double(k_block_side) / glm::max(hi - lo, glm::dvec2(1e-300));
    for (std::size_t k = 0; k < nodes.size(); ++k) {
        const glm::dvec3 p = to_glm(node_point(s, std::uint32_t(nodes[k])));
        const int cx = std::clamp(int((p.x - lo.x) * scale.x), 0, k_block_side - 1);
        const int cy = std::clamp(int((p.y - lo.y) * scale.y), 0, k_block_side - 1);
        cell_of_node[k] = std::uint8_t(cy * k_block_side + cx);
        ++start[cell_of_node[k] + 1];
    }
    for (int c = 0; c < cells; ++c)
        start[c + 1] += start[c];
    std::vector<std::int32_t> &order = fb.block_order_scratch;
    order.resize(nodes.size());
    std::array<std::uint32_t, cells> fill;
    std::copy(start.begin(), start.end() - 1, fill.begin());
    std::vector<Block> blocks;
    for (std::size_t k = 0; k < nodes.size(); ++k)
        order[fill[cell_of_node[k]]++] = std::int32_t(k);
    for (int c = 0; c < cells; ++c) {
        if (start[c] == start[c + 1])
            continue;
        Block b;
        b.head = nodes[std::size_t(order[start[c]])];
        b.count = start[c + 1] - start[c];
        glm::dvec3 blo(INFINITY), bhi(-INFINITY);
        double dev = 0.0;
        for (std::uint32_t k = start[c]; k < start[c + 1]; ++k) {
            const std::int32_t u = nodes[std::size_t(order[k])];
            const glm::dvec3 p = to_glm(node_point(s, std::uint32_t(u)));
            blo = glm::min(blo, p);
            bhi = glm::max(bhi, p);
            dev = std::max(dev, double(float_up(deviation(u))));
        }
        b.dev = dev;
        b.lo = blo;
        b.hi = bhi;
        blocks.push_back(b);
    }
    // Relink the list run by run.
    s.faces.face_head[f.idx()] = nodes[std::size_t(order.front())];
    for (std::size_t k = 0; k + 1 < order.size(); ++k)
        s.faces.next_swallowed[nodes[std::size_t(order[k])]] = nodes[std::size_t(order[k + 1])];
    s.faces.next_swallowed[nodes[std::size_t(order.back())]] = -1;
    fb.face_blocks[f.idx()] = std::move(blocks);
    fb.face_blocked[f.idx()] = 1;
    if (nodes.capacity() > k_kept_scratch) {
        // A face over a whole flat (10^5 nodes and more) is blocked once: its scratch goes.
        std::vector<std::int32_t>().swap(nodes);
        std::vector<std::uint8_t>().swap(fb.block_cell_scratch);
        std::vector<std::int32_t>().swap(fb.block_order_scratch);
    }
}

// Face f's tiles (corners a, b, c): kept ones, made now (tile_bounds) when the face is worth tiles,
// else null.
std::vector<float> *lattice_tiles(const EraserState &s, FaceBlocks &fb, FH f, std::uint32_t a,
                                  std::uint32_t b, std::uint32_t c, const TrianglePlane &plane) {
    if (fb.face_blocked[f.idx()]) {
        const auto kept = fb.face_tiles.find(f.idx());
        return kept == fb.face_tiles.end() ? nullptr : &kept->second;
    }
    const Tiling g = tiling(s, a, b, c);
    if (!worth_tiles(g))
        return nullptr;
    if (fb.tile_z.empty())
        build_tile_z(fb.tile_z, s.input);
    fb.face_blocked[f.idx()] = 1;
    return &(fb.face_tiles[f.idx()] = tile_bounds(s, fb.tile_z, g, a, b, c, plane));
}

} // namespace

std::pair<std::int32_t, double> worst_swallowed(EraserState &s, FrameState &frame, FH f,
                                                double above) {
    const Mesh &m = *s.input.mesh;
    std::int32_t u = s.faces.face_head[f.idx()];
    if (u < 0)
        return {-1, above};
    HH he = m.halfedge_handle(f);
    const glm::dvec3 a = to_glm(m.point(m.from_vertex_handle(he)));
    const glm::dvec3 b = to_glm(m.point(m.to_vertex_handle(he)));
    const glm::dvec3 c = to_glm(m.point(m.to_vertex_handle(m.next_halfedge_handle(he))));
    const TrianglePlane plane = s.input.xy ? TrianglePlane(a, b, c) : TrianglePlane();
    // A node's weight is looked up only when its deviation times a bound of the weights over the
    // face (TINs: over its corners' box in xy, within its largest deviation in z) could beat the
    // worst so far; that bound may clear the whole face at once (with a margin for the float
    // rounding of the stored deviation and of its recomputation here).
    std::pair<std::int32_t, double> worst{-1, above};
    double weight_bound = INFINITY;
    if (s.input.xy && !s.weights.unit_weights) {
        weight_bound = swallowed_weight_bound(s, a, b, c, s.faces.face_maxdev[f.idx()]);
        if (!(1.001 * double(s.faces.face_maxdev[f.idx()]) * weight_bound > above))
            return worst;
    }
    const bool screen = keeps_bounds(s, frame);
    const auto [box_lo, box_hi] = swallowed_box(s.faces, s.input.xy, f, a, b, c);
    if (screen && !(seen_bound(s, frame, f, box_lo, box_hi) > above))
        return worst;
    auto deviation_at = [&](const glm::dvec3 &p) {
        return node_deviation(s.input.xy, plane, p, a, b, c);
    };
    auto deviation = [&](std::int32_t u) {
        return deviation_at(to_glm(node_point(s, std::uint32_t(u))));
    };
    auto visit = [&](std::int32_t u, double dev, double bound) {
        if (!(dev * bound > worst.second))
            return;
        const double w = weighted(s, std::uint32_t(u), dev);
        if (w > worst.second)
            worst = {u, w};
    };
    if (s.input.grid_w > 0) {
        // Band by band, skipping a band whose largest weight cannot make the face's largest
        // deviation matter; or, on a large face, tile by tile with each tile's.
        const double dz = 1.001 * double(s.faces.face_maxdev[f.idx()]);
        const double zlo = std::min({a.z, b.z, c.z}) - dz, zhi = std::max({a.z, b.z, c.z}) + dz;
        const std::uint32_t ia = node_of(s, m.from_vertex_handle(he)),
                            ib = node_of(s, m.to_vertex_handle(he)),
                            ic = node_of(s, m.to_vertex_handle(m.next_halfedge_handle(he)));
        std::vector<float> *tiles = lattice_tiles(s, frame.blocks, f, ia, ib, ic, plane);
        // Visits sample(u, q, dev, bound) for each sample (point q, deviation dev) of a tile or
        // band whose largest deviation times its largest weight (`bound`) may exceed `above`.
        const auto scan = [&](const double &above, const auto &sample) {
            const auto bound_over = [&](const glm::dvec2 &lo, const glm::dvec2 &hi) {
                return s.weights.weigher.bound({lo, zlo}, {hi, zhi}) * k_rounded_weight;
            };
            if (tiles) {
                scan_tiles(
                    s, ia, ib, ic, *tiles,
                    [&](const glm::dvec2 &lo, const glm::dvec2 &hi, double dev) {
                        const double bound = bound_over(lo, hi);
                        return 1.001 * dev * bound > above ? bound : -1.0;
                    },
                    deviation_at, sample);
                return;
            }
            scan_lattice(
                s, ia, ib, ic,
                [&](const glm::dvec2 &lo, const glm::dvec2 &hi) {
                    if (s.weights.unit_weights)
                        return 1.0;
                    const double bound = bound_over(lo, hi);
                    return dz * bound > above ? bound : -1.0;
                },
                [&](std::uint32_t v, const Mesh::Point &p, double bound) {
                    const glm::dvec3 q = to_glm(p);
                    sample(v, q, deviation_at(q), bound);
                    return true;
                });
        };
        scan(worst.second, [&](std::uint32_t v, const glm::dvec3 &, double dev, double bound) {
            visit(std::int32_t(v), dev, bound);
        });
        if (screen && worst.first < 0) {
            // The largest weighted deviation, for the updates that follow: a band, tile or sample
            // that its bound shows cannot raise it is not weighed (the maximum is the same;
            // docs/decisions/007-seen-bounds.md).
            double seen = 0.0;
            scan(seen, [&](std::uint32_t, const glm::dvec3 &q, double dev, double bound) {
                if (dev * bound > seen)
                    seen = std::max(seen, dev * s.weights.weigher(q));
            });
            remember_seen(frame.seen, s.weights.weigher, f, seen, box_lo, box_hi);
        }
        return worst;
    }
    if (frame.blocks.face_blocked[f.idx()]) {
        for (const Block &block : frame.blocks.face_blocks.find(f.idx())->second) {
            const double bound = s.weights.weigher.bound(block.lo, block.hi) * k_rounded_weight;
            if (!(block.dev * bound > worst.second))
                continue;
            u = block.head;
            for (std::uint32_t k = 0; k < block.count; ++k, u = s.faces.next_swallowed[u])
                visit(u, deviation(u), bound);
        }
        return worst;
    }
    std::size_t length = 0;
    double seen = 0.0;
    for (; u >= 0; u = s.faces.next_swallowed[u], ++length) {
        const glm::dvec3 q = to_glm(node_point(s, std::uint32_t(u)));
        const double dev = deviation_at(q);
        visit(u, dev, weight_bound);
        if (screen)
            seen = std::max(seen, dev * s.weights.weigher(q));
    }
    if (screen && worst.first < 0)
        remember_seen(frame.seen, s.weights.weigher, f, seen, box_lo, box_hi);
    // A long list scanned whole gets blocks (when a weight bound can use them).
    if (std::isfinite(weight_bound) && length >= k_block_list)
        build_blocks(s, frame.blocks, f, glm::dvec2(glm::min(glm::min(a, b), c)),
                     glm::dvec2(glm::max(glm::max(a, b), c)), deviation);
    return worst;
}

} // namespace tinlod::refine
