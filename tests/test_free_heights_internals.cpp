// The free-heights pass's linear programme (ChebyshevFit, lib/src/erase/free_heights.hpp): the
// least L-infinity fit on small problems whose optimum is known in closed form or by a fine search,
// a solve after added rows against a fresh one, and the early stop. Its pre-check (BoxNarrowing)
// against the programme on problems made as the pass makes them, from real DEMs.
#include "erase/free_heights.hpp"

#include "assets.hpp"

#include "tinlod/raster.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using tinlod::erase::BoxNarrowing;
using tinlod::erase::ChebyshevFit;

namespace {

double worst(const std::vector<std::vector<double>> &a, const std::vector<double> &b,
             const std::vector<double> &z) {
    double most = 0.0;
    for (std::size_t i = 0; i < b.size(); ++i) {
        double s = -b[i];
        for (std::size_t k = 0; k < z.size(); ++k)
            s += a[i][k] * z[k];
        most = std::max(most, std::abs(s));
    }
    return most;
}

} // namespace

TEST(ChebyshevFit, OneVariableIsTheMidRange) {
    ChebyshevFit fit;
    fit.reset(1);
    for (const double b : {0.0, 1.0, 5.0}) {
        const double one = 1.0;
        fit.add_row(&one, b);
    }
    std::vector<double> z;
    EXPECT_NEAR(fit.solve(INFINITY, z), 2.5, 1e-12);
    EXPECT_NEAR(z[0], 2.5, 1e-12);
}

TEST(ChebyshevFit, CoupledRows) {
    // |z1|, |z2|, |z1 + z2 - 3| <= t: least t = 1 at z = (1, 1).
    ChebyshevFit fit;
    fit.reset(2);
    const double rows[3][2] = {{1, 0}, {0, 1}, {1, 1}};
    const double b[3] = {0, 0, 3};
    for (int i = 0; i < 3; ++i)
        fit.add_row(rows[i], b[i]);
    std::vector<double> z;
    EXPECT_NEAR(fit.solve(INFINITY, z), 1.0, 1e-12);
    EXPECT_NEAR(z[0], 1.0, 1e-12);
    EXPECT_NEAR(z[1], 1.0, 1e-12);
}

TEST(ChebyshevFit, RandomRowsAgainstAFineSearchAndAFreshSolve) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> weight(0.0, 1.0), target(-2.0, 2.0);
    for (int round = 0; round < 20; ++round) {
        // Rows as the pass makes them: unit rows, and barycentric weights on up to two variables.
        std::vector<std::vector<double>> a;
        std::vector<double> b;
        for (int k = 0; k < 2; ++k) {
            a.push_back({k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0});
            b.push_back(target(rng));
        }
        for (int i = 0; i < 12; ++i) {
            a.push_back({weight(rng) * 0.5, weight(rng) * 0.5});
            b.push_back(target(rng));
        }
        ChebyshevFit part, whole;
        part.reset(2);
        whole.reset(2);
        std::vector<double> z, y;
        for (std::size_t i = 0; i < b.size(); ++i) {
            whole.add_row(a[i].data(), b[i]);
            part.add_row(a[i].data(), b[i]);
            if (i == 5)
                part.solve(INFINITY, z); // then the rest come in after a solve
        }
        const double t = whole.solve(INFINITY, z);
        EXPECT_NEAR(worst(a, b, z), t, 1e-9);
        EXPECT_NEAR(part.solve(INFINITY, y), t, 1e-9);
        // No point of a fine grid fits better.
        double best = INFINITY;
        for (double x0 = -3.0; x0 <= 3.0; x0 += 0.01)
            for (double x1 = -3.0; x1 <= 3.0; x1 += 0.01)
                best = std::min(best, worst(a, b, {x0, x1}));
        EXPECT_LE(t, best + 1e-9);
        EXPECT_GE(t, best - 0.02);
        // Asked to give up under the optimum, it says it is over.
        ChebyshevFit early;
        early.reset(2);
        for (std::size_t i = 0; i < b.size(); ++i)
            early.add_row(a[i].data(), b[i]);
        EXPECT_GT(early.solve(0.5 * t, z), 0.5 * t);
    }
}

TEST(BoxNarrowing, RulesOutOnlyHolesTheProgrammeRulesOut) {
    // Problems as the pass makes them: a few variable nodes and a fixed one on lattice samples of a
    // real DEM, each at its sample's height, its change within the limit of its own sample (a unit
    // row), and the samples of triangles over them (barycentric rows, the residual from the plane
    // through the corners' heights). When the boxes rule a problem out the programme must find no
    // fit within the limit; when it finds one, its heights must lie in every box.
    std::mt19937 rng(11);
    int ruled_out = 0, over = 0, within = 0;
    for (const char *file : {"dem_srtm30.tif", "crater_u16.png"}) {
        const tinlod::Heightfield hf = tinlod::load_heightfield(tinlod::test::asset(file));
        const double zscale = std::string(file) == "crater_u16.png" ? 0.015625 : 1.0;
        std::uniform_int_distribution<int> cx(0, hf.width - 16), cy(0, hf.height - 16), off(0, 15),
            count(2, 5);
        for (int round = 0; round < 400; ++round) {
            const int x0 = cx(rng), y0 = cy(rng), nv = count(rng);
            const double limit = std::array<double, 3>{0.5, 2.0, 5.0}[round % 3];
            std::vector<std::array<int, 2>> at; // nv variable nodes, then a fixed one
            for (int k = 0; k <= nv; ++k)
                at.push_back({x0 + off(rng), y0 + off(rng)});
            const auto height = [&](int x, int y) { return zscale * double(hf.at(x, y)); };
            std::vector<std::vector<double>> a;
            std::vector<double> b;
            std::vector<std::array<int, 3>> vars;
            std::vector<std::array<double, 3>> weights;
            for (int k = 0; k < nv; ++k) {
                a.push_back(std::vector<double>(std::size_t(nv), 0.0));
                a.back()[std::size_t(k)] = 1.0;
                b.push_back(0.0);
                vars.push_back({k, -1, -1});
                weights.push_back({1.0, 0.0, 0.0});
            }
            for (int i = 0; i <= nv; ++i)
                for (int j = i + 1; j <= nv; ++j)
                    for (int l = j + 1; l <= nv; ++l) {
                        const std::array<int, 3> c = {i, j, l};
                        const auto area = [&](int p, int q, int x, int y) {
                            return double(at[std::size_t(p)][0] - x) *
                                       double(at[std::size_t(q)][1] - y) -
                                   double(at[std::size_t(p)][1] - y) *
                                       double(at[std::size_t(q)][0] - x);
                        };
                        const double whole =
                            area(j, l, at[std::size_t(i)][0], at[std::size_t(i)][1]);
                        if (std::abs(whole) < 1.0)
                            continue;
                        for (int y = y0; y < y0 + 16; ++y)
                            for (int x = x0; x < x0 + 16; ++x) {
                                const std::array<double, 3> w = {area(j, l, x, y) / whole,
                                                                 area(l, i, x, y) / whole,
                                                                 area(i, j, x, y) / whole};
                                if (w[0] < 0.0 || w[1] < 0.0 || w[2] < 0.0)
                                    continue;
                                std::vector<double> row(std::size_t(nv), 0.0);
                                std::array<int, 3> var = {-1, -1, -1};
                                double plane = 0.0;
                                for (std::size_t k = 0; k < 3; ++k) {
                                    const auto &p = at[std::size_t(c[k])];
                                    plane += w[k] * height(p[0], p[1]);
                                    if (c[k] < nv) {
                                        row[std::size_t(c[k])] = w[k];
                                        var[k] = c[k];
                                    }
                                }
                                a.push_back(row);
                                b.push_back(height(x, y) - plane);
                                vars.push_back(var);
                                weights.push_back(w);
                            }
                    }
            ChebyshevFit fit;
            fit.reset(nv);
            for (std::size_t i = 0; i < b.size(); ++i)
                fit.add_row(a[i].data(), b[i]);
            std::vector<double> z;
            const double t = fit.solve(INFINITY, z);
            if (std::isinf(t))
                continue;
            BoxNarrowing boxes;
            boxes.reset(std::vector<double>(std::size_t(nv), -limit),
                        std::vector<double>(std::size_t(nv), limit), limit);
            bool out = false;
            for (int sweep = 0; sweep < 2 && !out; ++sweep)
                for (std::size_t i = 0; i < b.size() && !out; ++i)
                    out = !boxes.add(vars[i], weights[i], b[i]);
            SCOPED_TRACE(std::string(file) + " round " + std::to_string(round));
            if (out) {
                ++ruled_out;
                EXPECT_GT(t, limit);
            }
            if (t > limit) {
                ++over;
                continue;
            }
            ++within;
            for (int k = 0; k < nv; ++k) {
                EXPECT_GE(z[std::size_t(k)], boxes.low(k) - 1e-6);
                EXPECT_LE(z[std::size_t(k)], boxes.high(k) + 1e-6);
            }
        }
    }
    // Both kinds occur, and the boxes rule out most of the problems over the limit.
    EXPECT_GT(within, 50);
    EXPECT_GT(over, 50);
    EXPECT_GT(ruled_out, over / 2);
}

// The pass's stepped scan (scan_stepped) on triangles over a real DEM against each sample of
// visit_inside (the erase's scan) weighed here by its own cross products: the samples it visits
// come in visit_inside's order with their doubled areas; every sample whose planes miss the test
// by over 1e-9 m is visited, every one passed over keeps it within 1e-9 m; and the largest miss
// over the samples, tracked with the thresholds moving as the pass's reach tests move them, is
// the largest a full scan finds, to the bit.
TEST(ScanStepped, VisitsWhatTheTestCannotPassOver) {
    const tinlod::Heightfield hf = tinlod::load_heightfield(tinlod::test::asset("crater_u16.png"));
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> cx(0, hf.width - 48), cy(0, hf.height - 48), off(0, 47);
    std::uniform_real_distribution<double> room(0.0, 3.0);
    int triangles = 0, visited = 0, passed = 0;
    for (int trial = 0; trial < 600; ++trial) {
        const int x0 = cx(rng), y0 = cy(rng);
        std::int64_t x[3], y[3];
        for (int k = 0; k < 3; ++k) {
            x[k] = x0 + off(rng);
            y[k] = y0 + off(rng);
        }
        std::int64_t o = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
        if (o < 0) {
            std::swap(x[1], x[2]);
            std::swap(y[1], y[2]);
            o = -o;
        }
        if (o == 0 || tinlod::box_samples(x, y) <= tinlod::k_small_box)
            continue;
        ++triangles;
        std::array<double, 3> h, down, up;
        for (std::size_t k = 0; k < 3; ++k) {
            h[k] = double(hf.at(int(x[k]), int(y[k])));
            down[k] = h[k] + room(rng);
            up[k] = h[k] - room(rng);
        }
        const auto areas = [&](std::int64_t c, std::int64_t r) {
            std::array<std::int64_t, 3> a;
            for (int k = 0; k < 3; ++k) {
                const int b = (k + 1) % 3, d = (k + 2) % 3;
                a[std::size_t(k)] = (x[b] - c) * (y[d] - r) - (y[b] - r) * (x[d] - c);
            }
            return a;
        };
        const auto plane = [&](const std::array<double, 3> &z,
                               const std::array<std::int64_t, 3> &a) {
            return (double(a[0]) * z[0] + double(a[1]) * z[1] + double(a[2]) * z[2]) / double(o);
        };
        std::vector<std::array<std::int64_t, 2>> all, seen;
        tinlod::visit_inside(x, y, [&](std::int64_t c, std::int64_t r) {
            all.push_back({c, r});
            return true;
        });
        // Fixed thresholds: about half the samples pass.
        const double floor = -1.5, ceiling = 1.5;
        bool same_areas = true;
        tinlod::erase::scan_stepped(
            hf, x, y, down, up, floor, ceiling,
            [&](std::int64_t c, std::int64_t r, double sa, double sb, double sc) {
                const auto a = areas(c, r);
                same_areas =
                    same_areas && sa == double(a[0]) && sb == double(a[1]) && sc == double(a[2]);
                seen.push_back({c, r});
                return true;
            });
        EXPECT_TRUE(same_areas) << "trial " << trial;
        std::size_t next = 0;
        for (const auto &s : all) {
            const auto a = areas(s[0], s[1]);
            const double z = double(hf.at(int(s[0]), int(s[1])));
            const double l = plane(down, a) - z, u = plane(up, a) - z;
            const bool is_seen = next < seen.size() && seen[next] == s;
            if (is_seen) {
                ++next;
                ++visited;
            } else {
                ++passed;
                EXPECT_TRUE(l >= floor - 1e-9 && u <= ceiling + 1e-9) << "trial " << trial;
            }
            if (l < floor - 1e-9 || u > ceiling + 1e-9) {
                EXPECT_TRUE(is_seen) << "trial " << trial;
            }
        }
        EXPECT_EQ(next, seen.size()) << "visited out of order or outside, trial " << trial;
        // The reach tests' use: the largest |z - p| - m, p the plane through the corners' samples,
        // m through their rooms (here 1.5 m each), the thresholds following the largest so far.
        const std::array<double, 3> m = {1.5, 1.5, 1.5};
        const auto miss = [&](std::int64_t c, std::int64_t r) {
            const auto a = areas(c, r);
            return std::abs(double(hf.at(int(c), int(r))) - plane(h, a)) - plane(m, a);
        };
        double full = 0.0;
        for (const auto &s : all)
            full = std::max(full, miss(s[0], s[1]));
        std::array<double, 3> raised, lowered;
        for (std::size_t k = 0; k < 3; ++k) {
            raised[k] = h[k] + m[k];
            lowered[k] = h[k] - m[k];
        }
        double most = 0.0, top = most - 1e-6, bottom = -top;
        tinlod::erase::scan_stepped(hf, x, y, raised, lowered, bottom, top,
                                    [&](std::int64_t c, std::int64_t r, double, double, double) {
                                        most = std::max(most, miss(c, r));
                                        top = most - 1e-6;
                                        bottom = -top;
                                        return true;
                                    });
        EXPECT_EQ(most, full) << "trial " << trial;
    }
    EXPECT_GT(triangles, 200);
    EXPECT_GT(visited, 1000);
    EXPECT_GT(passed, 1000); // the test passes some over, and visits some
}
