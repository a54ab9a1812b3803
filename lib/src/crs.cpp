// WGS 84 and its UTM zones (crs.hpp), other CRSs through PROJ.
//
// UTM is the transverse Mercator projection by Krüger's series, to sixth order in the third
// flattening n (K. Engsager, K. Poder, "A highly accurate world wide algorithm for the transverse
// Mercator mapping (almost)", ICC 2007; C. F. F. Karney, "Transverse Mercator with an accuracy of
// a few nanometers", J. Geodesy 85, 2011, eqs. 11-14 and 35): latitude to conformal latitude, the
// spherical transverse Mercator, then the series that maps it onto the ellipsoid's. PROJ 9 uses
// the same series for UTM, and tinlod's rasters were placed by PROJ: every sum and product below
// is evaluated in the order PROJ 9.1 evaluates it, so that the results are PROJ's to the last bit
// (test_startup compares them over every zone); an algebraically equal reordering rounds
// otherwise and would move every vertex of a TIN.
#include "crs.hpp"
#include "backends/backends.hpp"
#include "tinlod/error.hpp"

#include <algorithm>
#include <cmath>

namespace tinlod::crs {

namespace {

constexpr int k_wgs84 = 4326;
constexpr int k_utm_north = 32600, k_utm_south = 32700;

// The UTM zone EPSG:`epsg` names (1..60; `south` set for the southern ones), or 0.
int utm_zone(int epsg, bool &south) {
    south = epsg > k_utm_south;
    const int zone = epsg - (south ? k_utm_south : k_utm_north);
    return epsg > k_utm_north && zone >= 1 && zone <= 60 ? zone : 0;
}

// Coefficients of sin(2k x), k = 1..6, each a polynomial in n.
constexpr int k_terms = 6;
using Series = std::array<double, k_terms>;

// c[0] + x (c[1] + x (c[2] + ...)).
template <std::size_t N> double horner(double x, const std::array<double, N> &c) {
    double h = c[N - 1];
    for (std::size_t k = N - 1; k-- > 0;)
        h = c[k] + x * h;
    return h;
}

// theta + sum of c[k] sin(2 (k + 1) theta), by Clenshaw's recurrence on cos 2 theta.
double add_sines(const Series &c, double theta, double sin_2theta, double cos_2theta) {
    const double twice_cos = 2 * cos_2theta;
    double b = 0, b1 = c[k_terms - 1], b2 = 0;
    for (int k = k_terms - 2; k >= 0; --k) {
        b = -b2 + twice_cos * b1 + c[k];
        b2 = b1;
        b1 = b;
    }
    return theta + b * sin_2theta;
}

// xi + i eta plus the sum of c[k] sin(2 (k + 1) (xi + i eta)), by Clenshaw's recurrence in
// complex numbers, from the sine and cosine of 2 xi and the hyperbolic ones of 2 eta.
void add_complex_sines(const Series &c, double sin_2xi, double cos_2xi, double sinh_2eta,
                       double cosh_2eta, double &xi, double &eta) {
    // 2 cos(2 (xi + i eta)) = two_re + i two_im.
    const double two_re = 2 * cos_2xi * cosh_2eta, two_im = -2 * sin_2xi * sinh_2eta;
    double re = c[k_terms - 1], im = 0, re1 = 0, im1 = 0;
    for (int k = k_terms - 2; k >= 0; --k) {
        const double re2 = re1, im2 = im1;
        re1 = re;
        im1 = im;
        re = -re2 + two_re * re1 - two_im * im1 + c[k];
        im = -im2 + two_im * re1 + two_re * im1;
    }
    // Times sin(2 (xi + i eta)).
    const double s_re = sin_2xi * cosh_2eta, s_im = cos_2xi * sinh_2eta;
    const double d_xi = s_re * re - s_im * im;
    const double d_eta = s_re * im + s_im * re;
    xi += d_xi;
    eta += d_eta;
}

// A longitude in radians brought into [-pi, pi] (one slightly past either end is kept).
double wrap_longitude(double lambda) {
    if (std::fabs(lambda) < M_PI + 1e-12)
        return lambda;
    lambda += M_PI;
    lambda -= 2 * M_PI * std::floor(lambda / (2 * M_PI));
    return lambda - M_PI;
}

// One UTM zone on WGS 84.
struct Zone {
    double a = 0;           // semi-major axis, metres
    double k0_a_over_a = 0; // k0 times the rectifying radius, in units of a
    double central = 0;     // central meridian, radians
    double false_northing = 0;
    Series to_conformal = {}; // latitude to conformal latitude (Karney eq. 11-12)
    Series to_mercator = {};  // the sphere's transverse Mercator to the ellipsoid's (alpha_k)
};

Zone make_zone(int zone, bool south) {
    // Read at run time, as PROJ reads its ellipsoid table: a compiler folding the square root,
    // arc sine, tangent and power of constants may round otherwise than the C library does.
    static volatile const double k_a = 6378137.0, k_inverse_flattening = 298.257223563;
    Zone z;
    z.a = k_a;
    const double f = 1 / k_inverse_flattening;
    const double e2 = 2 * f - f * f;
    // The third flattening from the angular eccentricity: n = tan^2(asin(e) / 2).
    const double n = std::pow(std::tan(std::asin(std::sqrt(e2)) / 2), 2);
    const double n2 = n * n, n3 = n2 * n, n4 = n3 * n, n5 = n4 * n, n6 = n5 * n;
    z.to_conformal = {
        n * horner(n, std::array{-2.0, 2 / 3.0, 4 / 3.0, -82 / 45.0, 32 / 45.0, 4642 / 4725.0}),
        n2 * horner(n, std::array{5 / 3.0, -16 / 15.0, -13 / 9.0, 904 / 315.0, -1522 / 945.0}),
        n3 * horner(n, std::array{-26 / 15.0, 34 / 21.0, 8 / 5.0, -12686 / 2835.0}),
        n4 * horner(n, std::array{1237 / 630.0, -12 / 5.0, -24832 / 14175.0}),
        n5 * horner(n, std::array{-734 / 315.0, 109598 / 31185.0}),
        n6 * (444337 / 155925.0)};
    z.to_mercator = {
        n * horner(n,
                   std::array{0.5, -2 / 3.0, 5 / 16.0, 41 / 180.0, -127 / 288.0, 7891 / 37800.0}),
        n2 * horner(n, std::array{13 / 48.0, -3 / 5.0, 557 / 1440.0, 281 / 630.0,
                                  -1983433 / 1935360.0}),
        n3 * horner(n, std::array{61 / 240.0, -103 / 140.0, 15061 / 26880.0, 167603 / 181440.0}),
        n4 * horner(n, std::array{49561 / 161280.0, -179 / 168.0, 6601661 / 7257600.0}),
        n5 * horner(n, std::array{34729 / 80640.0, -3418889 / 1995840.0}),
        n6 * (212378941 / 319334400.0)};
    // UTM: scale 0.9996 on the central meridian, origin on the equator (whose northing adds
    // nothing), false easting 500 km, false northing 10,000 km in the south.
    const double k0 = 0.9996;
    z.k0_a_over_a = k0 / (1 + n) * horner(n2, std::array{1.0, 1 / 4.0, 1 / 64.0, 1 / 256.0});
    z.central = (zone - 0.5) * M_PI / 30 - M_PI;
    z.false_northing = south ? 10000000.0 : 0.0;
    return z;
}

// Longitude and latitude in radians to easting and northing in metres; HUGE_VAL outside the
// projection's domain (more than about 85 degrees of arc from the central meridian).
std::array<double, 2> project(const Zone &z, double lambda, double phi) {
    constexpr std::array<double, 2> k_outside = {HUGE_VAL, HUGE_VAL};
    if (std::fabs(phi) - M_PI_2 > 1e-12 || lambda > 10 || lambda < -10)
        return k_outside;
    phi = std::clamp(phi, -M_PI_2, M_PI_2);
    lambda = wrap_longitude(wrap_longitude(lambda) - z.central);
    const double chi = add_sines(z.to_conformal, phi, std::sin(2 * phi), std::cos(2 * phi));
    const double sin_chi = std::sin(chi), cos_chi = std::cos(chi);
    const double sin_lambda = std::sin(lambda), cos_lambda = std::cos(lambda);
    // The sphere's transverse Mercator: xi = atan2(sin chi, cos chi cos lambda), and
    // eta = asinh(tan_eta) with tan_eta = sin lambda cos chi / d, d = hypot(sin chi, cos chi cos
    // lambda). With 1 / d = cosh eta, the double angles follow without more trigonometry:
    // sin 2 xi = 2 sin chi cos chi cos lambda / d^2, cos 2 xi = 2 (cos chi cos lambda / d)^2 - 1,
    // sinh 2 eta = 2 tan_eta / d, cosh 2 eta = 2 / d^2 - 1.
    const double along = cos_chi * cos_lambda;
    double xi = std::atan2(sin_chi, along);
    const double inv_d = 1. / std::hypot(sin_chi, along);
    const double tan_eta = sin_lambda * cos_chi * inv_d;
    double eta = std::asinh(tan_eta);
    const double two_inv_d = 2 * inv_d, two_inv_d2 = two_inv_d * inv_d;
    const double along_two_inv_d2 = along * two_inv_d2;
    add_complex_sines(z.to_mercator, sin_chi * along_two_inv_d2, along * along_two_inv_d2 - 1,
                      tan_eta * two_inv_d, two_inv_d2 - 1, xi, eta);
    if (!(std::fabs(eta) <= 2.623395162778))
        return k_outside;
    // In units of a, then metres, then the false easting and northing.
    const double x = z.k0_a_over_a * eta * z.a + 500000.0;
    const double y = z.k0_a_over_a * xi * z.a + z.false_northing;
    return {x, y};
}

// Degrees to radians, PROJ's factor.
constexpr double k_radians_per_degree = M_PI / 180;

} // namespace

std::array<double, 2> wgs84_to_utm(int zone, bool south, double lon, double lat) {
    return project(make_zone(zone, south), lon * k_radians_per_degree, lat * k_radians_per_degree);
}

void check(const std::string &path, int epsg, bool geographic) {
    bool south = false;
    const bool known_geographic = epsg == k_wgs84, known_projected = utm_zone(epsg, south) > 0;
    if (!known_geographic && !known_projected)
        return backends::crs_library().check_crs(path, epsg, geographic);
    if (geographic != known_geographic)
        throw Error(path, "EPSG:" + std::to_string(epsg) + " is not a " +
                              (geographic ? "geographic" : "projected") +
                              " CRS, yet the file's GeoKeys say it is one");
}

Transformation::Transformation(const std::string &path, int from, int to) {
    if (from == to)
        return;
    utm_zone_ = from == k_wgs84 ? utm_zone(to, south_) : 0;
    if (utm_zone_ == 0)
        proj_ = backends::crs_library().transformation(path, from, to);
}

Transformation::~Transformation() = default;

std::vector<glm::dvec2> Transformation::apply(std::span<const glm::dvec2> points) const {
    std::vector<std::array<double, 2>> xy;
    xy.reserve(points.size());
    for (const glm::dvec2 &p : points)
        xy.push_back({p.x, p.y});
    if (utm_zone_ > 0) {
        const Zone z = make_zone(utm_zone_, south_);
        for (auto &p : xy)
            p = project(z, p[0] * k_radians_per_degree, p[1] * k_radians_per_degree);
    } else if (proj_) {
        proj_->apply(xy);
    }
    std::vector<glm::dvec2> out;
    out.reserve(xy.size());
    // Outside the domain, PROJ and project() give HUGE_VAL.
    for (const auto &p : xy)
        out.push_back(std::isfinite(p[0]) && std::isfinite(p[1]) && std::abs(p[0]) < 1e30 &&
                              std::abs(p[1]) < 1e30
                          ? glm::dvec2(p[0], p[1])
                          : glm::dvec2(NAN));
    return out;
}

} // namespace tinlod::crs
