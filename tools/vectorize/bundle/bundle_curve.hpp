// Smoothing a bundle (docs/bundles.md "Smoothing"): its network polyline
// becomes a clamped cubic B-spline whose control points are polyline
// vertices, chosen per zoom so the curve stays within a corridor of the
// polyline (--corridor-px pixels of that zoom): the coarsest zoom starts from
// the two ends, and each finer zoom refines the coarser one's control points
// (a control-point hierarchy), adding the vertex farthest from the chord of
// a span that leaves the corridor, or, between neighbouring vertices, making
// both ends sharp (a triple control point the curve passes through; a
// polyline of sharp points is drawn exactly). The ends are always on the
// curve, so bundles that meet at a node still meet after smoothing.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "lines/line_geometry.hpp"

namespace globe {

// Control points: ascending polyline vertex indices (first and last always
// there) and whether each is sharp. An end with a tangent (a unit direction,
// the way the curve leaves its first point or arrives at its last; {0, 0} =
// free) gets one more control point on that tangent, a third of the way to
// its neighbour, unless the end is sharp: so curves that meet at a junction
// with the same tangent join without a kink.
struct ControlPoints {
  std::vector<uint32_t> index;
  std::vector<uint8_t> sharp;
  XY start_tangent{0, 0}, end_tangent{0, 0};
  bool operator==(const ControlPoints&) const = default;
};

// The curve of `controls` over `poly`, sampled about every `step` (4 to 64
// points per span), both ends included.
std::vector<XY> evaluate_curve(std::span<const XY> poly, const ControlPoints& controls,
                               double step);

// One drawn version of a bundle: the zooms it serves (bit z) and its curve.
struct CurveLevel {
  uint32_t zooms = 0;
  std::vector<XY> curve;
};

// The hierarchy for zooms min_zoom..max_zoom: tolerance[z] is the corridor's
// half width at zoom z and step[z] the sampling step, in the units of
// `poly` (both indexed by zoom). Zooms with the same control points share a
// level (sampled at the finest of them).
std::vector<CurveLevel> smooth_bundle(std::span<const XY> poly, int min_zoom, int max_zoom,
                                      std::span<const double> tolerance,
                                      std::span<const double> step, XY start_tangent = {0, 0},
                                      XY end_tangent = {0, 0});

// Junction tangents (docs/bundles.md "Smoothing"): where bundles meet at a
// network node, the axis their legs agree on (the weighted mean of the
// legs' directions taken modulo 180 degrees: the heavier corridor leads); each
// bundle end there takes that axis, pointing along the bundle. Ends at nodes
// where one bundle ends, or whose legs do not agree on an axis, stay free.
// polys: per bundle, its polyline (in a plane); ends: per bundle, its first
// and last node; returns per bundle {start tangent, end tangent}.
std::vector<std::pair<XY, XY>> junction_tangents(
    std::span<const std::vector<XY>> polys, std::span<const std::pair<uint32_t, uint32_t>> ends,
    std::span<const double> weights);

}  // namespace globe
