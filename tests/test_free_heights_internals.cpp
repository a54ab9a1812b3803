// The free-heights pass's linear programme (ChebyshevFit, lib/src/erase/free_heights.hpp): the
// least L-infinity fit on small problems whose optimum is known in closed form or by a fine search,
// a solve after added rows against a fresh one, and the early stop.
#include "erase/free_heights.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

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
