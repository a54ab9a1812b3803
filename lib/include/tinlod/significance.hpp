// The significance parameter SP of a TIN node (paper step 2: SP = f(OD, OA, sration)), in three
// models behind one interface, plus the per-node screen weight the erase bound is measured with.
// The erase computes the SP of erasing a node (its deviation measured against the re-triangulated
// hole) in lib/src/erase/erase_cost.cpp, evaluate() into Hole::sp; the weight's one definition
// is the Weigher of tinlod/screen_weight.hpp. Formulas: docs/method.md.
//
// Terms of a node P seen from a View (all in the local world frame, metres):
//   OD      observation distance |P - eye|
//   OA      observation angle between the observation axis (eye -> at, which meets the surface at
//           the focal point, see focal.hpp) and the line of sight eye -> P, radians
//   delta   deviation of P from the surface its neighbours span once it is gone: the vertical
//           distance (TINs) or the distance to the nearest new triangle (general meshes) of the
//           re-triangulated hole
//   sration terrain projection ratio, simplified as in the paper to delta / L, L = mean distance
//           from P to its ring neighbours (dimensionless)
//
// Models:
//   screen (default)  SP = delta * k / OD * peripheral(OA)     [pixels]
//       k = viewport_h / (2 tan(fov/2)) (docs/method.md): the pixels by which erasing P shifts the
//       picture. peripheral(OA) = 1 inside the view frustum (with cone_margin_px of slack) and
//       inside the cone around the axis that circumscribes the frustum; beyond that cone, whose
//       half-angle is A = atan(half viewport diagonal / k), it decays as
//       max(floor, exp(-(OA - A) / falloff)).
//   paper             SP = sration^w_ration * (D_f / OD)^w_distance * cos(min(OA, pi/2) /
//   2)^w_angle
//       the paper's f with explicit weights (exponents), D_f = distance from the eye to the focal
//       point. Dimensionless: it orders nodes only; the erase bound stays the screen one.
//   vertical          SP = delta                                [world units]
//       view-independent (`--max-error`): every node weighs 1.
#pragma once

#include "tinlod/tin.hpp"
#include "tinlod/view.hpp"

#include <glm/glm.hpp>

#include <vector>

namespace tinlod {

enum class SpModel { screen, paper, vertical };

struct SignificanceOptions {
    SpModel model = SpModel::screen;
    double cone_margin_px = 2.0; // pixels of slack around the frustum still counted as inside
    // outside the view cone the peripheral factor e-folds every this many degrees
    double falloff_deg = 15.0;
    double floor = 0.02;     // smallest peripheral factor (far behind the observer)
    double w_distance = 1.0; // paper model: exponent of D_f / OD
    double w_angle = 1.0;    // paper model: exponent of cos(OA / 2)
    double w_ration = 1.0;   // paper model: exponent of sration
};

// The per-node terms of SP (see the file comment).
struct NodeTerms {
    double od = 0.0;         // world units
    double oa = 0.0;         // radians, in [0, pi]
    double delta = 0.0;      // world units
    double ration = 0.0;     // dimensionless
    double peripheral = 1.0; // peripheral_factor of the node, in [floor, 1]
};

// OA of p: angle between view.axis() and p - eye, radians.
double observation_angle(const View &view, const glm::dvec3 &p);

// peripheral(OA) of p, in [floor, 1] (1 inside the frustum): Weigher(view, options).peripheral(p).
double peripheral_factor(const View &view, const glm::dvec3 &p, const SignificanceOptions &options);

// k / OD * peripheral(OA): pixels per world unit of deviation at p; the weight by which the erase
// bound turns a node's deviation into pixels (Weigher(view, options)(p), whatever options.model).
// Infinite at the eye.
double screen_weight(const View &view, const glm::dvec3 &p, const SignificanceOptions &options);

// SP of a node from its terms. `view` may be null only for SpModel::vertical; `focal_distance`
// (D_f, world units) is used by the paper model only.
double significance(const NodeTerms &terms, const View *view, const SignificanceOptions &options,
                    double focal_distance = 1.0);

// screen_weight of every vertex, indexed by vertex idx (deleted vertices included); 1 everywhere
// without a view or for SpModel::vertical.
std::vector<float> node_weights(const Mesh &mesh, const View *view,
                                const SignificanceOptions &options);

// SP of every live vertex (indexed by vertex idx; 0 for deleted ones), with delta measured against
// the plane through its ring's centroid normal to the fan's area-weighted normal (the quick,
// one-off estimate used to colour renders; the decimater measures delta against the re-triangulated
// hole instead). Boundary vertices get +infinity: they are not erased by significance alone.
std::vector<float> node_significance(const Mesh &mesh, const View *view,
                                     const SignificanceOptions &options);

} // namespace tinlod
