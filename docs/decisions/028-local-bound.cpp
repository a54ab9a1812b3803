// The per-sample local bound of docs/decisions/028-fewest-2.md. A sample is "needed at radius r"
// when no triangle over three other lattice samples within Chebyshev distance r of it covers it
// (closed) with every lattice sample in the triangle within M of its plane. Of the needed, it
// counts those a unimodular sliver (the sample its only inner sample, at its centroid; corners
// within sliverR) holds within M. usage: 028-local-bound F32 W H M R [sliverR]
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>
using i64 = long long;
static int W, H;
static std::vector<float> z;
static double M;
static double Z(i64 x, i64 y) { return z[size_t(y * W + x)]; }
static i64 orient(i64 ax, i64 ay, i64 bx, i64 by, i64 cx, i64 cy) {
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}
// every lattice sample in the closed triangle within M of the plane (exact barycentric, area 2A)
static bool valid(i64 ax, i64 ay, i64 bx, i64 by, i64 cx, i64 cy) {
    i64 A = orient(ax, ay, bx, by, cx, cy);
    if (A < 0) {
        std::swap(bx, cx);
        std::swap(by, cy);
        A = -A;
    }
    const double za = Z(ax, ay), zb = Z(bx, by), zc = Z(cx, cy);
    i64 x0 = std::min({ax, bx, cx}), x1 = std::max({ax, bx, cx});
    i64 y0 = std::min({ay, by, cy}), y1 = std::max({ay, by, cy});
    for (i64 y = y0; y <= y1; ++y)
        for (i64 x = x0; x <= x1; ++x) {
            i64 s0 = orient(bx, by, cx, cy, x, y), s1 = orient(cx, cy, ax, ay, x, y),
                s2 = orient(ax, ay, bx, by, x, y);
            if (s0 < 0 || s1 < 0 || s2 < 0)
                continue;
            double p = (za * s0 + zb * s1 + zc * s2) / double(A);
            if (std::abs(p - Z(x, y)) > M + 1e-9)
                return false;
        }
    return true;
}
int main(int argc, char **argv) {
    W = atoi(argv[2]);
    H = atoi(argv[3]);
    M = atof(argv[4]);
    int R = atoi(argv[5]);
    int SR = argc > 6 ? atoi(argv[6]) : 0;
    z.resize(size_t(W) * H);
    FILE *f = fopen(argv[1], "rb");
    if (fread(z.data(), 4, z.size(), f) != z.size())
        return 1;
    std::vector<std::pair<int, int>> off;
    for (int dy = -R; dy <= R; ++dy)
        for (int dx = -R; dx <= R; ++dx)
            if (dx || dy)
                off.push_back({dx, dy});
    // nearer candidates first: most samples are covered by a small triangle
    std::sort(off.begin(), off.end(), [](auto a, auto b) {
        return std::max(std::abs(a.first), std::abs(a.second)) <
               std::max(std::abs(b.first), std::abs(b.second));
    });
    i64 need_int = 0, need_b = 0, sliver = 0;
    std::vector<std::uint8_t> need(z.size());
    for (i64 sy = 0; sy < H; ++sy)
        for (i64 sx = 0; sx < W; ++sx) {
            const double zs = Z(sx, sy);
            bool found = false;
            std::vector<int> cand;
            for (int i = 0; i < int(off.size()); ++i) {
                i64 x = sx + off[i].first, y = sy + off[i].second;
                if (x >= 0 && y >= 0 && x < W && y < H)
                    cand.push_back(i);
            }
            const int n = int(cand.size());
            for (int c = 2; c < n && !found; ++c) // c the farthest: triangles by growing size
                for (int a = 0; a < c && !found; ++a)
                    for (int b = a + 1; b < c && !found; ++b) {
                        i64 ax = sx + off[cand[a]].first, ay = sy + off[cand[a]].second;
                        i64 bx = sx + off[cand[b]].first, by = sy + off[cand[b]].second;
                        i64 cx = sx + off[cand[c]].first, cy = sy + off[cand[c]].second;
                        i64 A = orient(ax, ay, bx, by, cx, cy);
                        if (A == 0)
                            continue;
                        i64 s0 = orient(bx, by, cx, cy, sx, sy),
                            s1 = orient(cx, cy, ax, ay, sx, sy),
                            s2 = orient(ax, ay, bx, by, sx, sy);
                        if (A < 0) {
                            s0 = -s0;
                            s1 = -s1;
                            s2 = -s2;
                            A = -A;
                        }
                        if (s0 < 0 || s1 < 0 || s2 < 0)
                            continue;
                        double p = (Z(ax, ay) * s0 + Z(bx, by) * s1 + Z(cx, cy) * s2) / double(A);
                        if (std::abs(p - zs) > M + 1e-9)
                            continue;
                        found = valid(ax, ay, bx, by, cx, cy);
                    }
            if (!found) {
                need[size_t(sy * W + sx)] = 1;
                bool border = sx == 0 || sy == 0 || sx == W - 1 || sy == H - 1;
                (border ? need_b : need_int)++;
                // a unimodular sliver (s its only interior sample, at its centroid) within SR
                bool sl = false;
                for (int ux = -SR; ux <= SR && !sl; ++ux)
                    for (int uy = -SR; uy <= SR && !sl; ++uy)
                        for (int vx = -SR; vx <= SR && !sl; ++vx)
                            for (int vy = -SR; vy <= SR && !sl; ++vy) {
                                if (std::abs(i64(ux) * vy - i64(uy) * vx) != 1)
                                    continue;
                                i64 p[3][2] = {{sx + ux, sy + uy},
                                               {sx + vx, sy + vy},
                                               {sx - ux - vx, sy - uy - vy}};
                                bool in = true;
                                for (auto &q : p)
                                    in = in && q[0] >= 0 && q[1] >= 0 && q[0] < W && q[1] < H;
                                if (!in)
                                    continue;
                                double m = (Z(p[0][0], p[0][1]) + Z(p[1][0], p[1][1]) +
                                            Z(p[2][0], p[2][1])) /
                                           3;
                                sl = std::abs(m - zs) <= M + 1e-9;
                            }
                sliver += sl;
            }
        }
    i64 tri = 2 * need_int + need_b - 2;
    printf("M %g r %d needed: interior %lld border %lld -> triangles >= %lld; of the needed, %lld "
           "covered by a sliver within %d\n",
           M, R, need_int, need_b, tri, sliver, SR);
}
