// The window's orbit camera (viewer/camera/orbit): a pose survives the trip
// through an orbit on both surfaces; on the globe, panning moves the target
// by the metres asked over the ellipsoid, zooming towards a point keeps the
// eye on the line to it, and an orbit over a pole or the antimeridian gives
// valid poses. Checked with plain spherical/ellipsoidal formulas here.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "camera/ellipsoid.hpp"
#include "camera/orbit.hpp"

namespace {

using namespace globe::viewer;
using tileformat::Tiling;

void expect_same_pose(const CameraPose& a, const CameraPose& b, const std::string& what) {
  EXPECT_NEAR(std::remainder(a.lon - b.lon, 360.0), 0, 1e-6) << what;
  EXPECT_NEAR(a.lat, b.lat, 1e-6) << what;
  EXPECT_NEAR(a.height_m, b.height_m, 1e-3 * std::max(1.0, a.height_m / 1000)) << what;
  EXPECT_NEAR(std::remainder(a.heading_deg - b.heading_deg, 360.0), 0, 1e-5) << what;
  EXPECT_NEAR(a.pitch_deg, b.pitch_deg, 1e-5) << what;
}

TEST(Orbit, PosesSurviveTheRoundTripOnBothSurfaces) {
  for (Surface surface : {Surface::kFlat, Surface::kGlobe}) {
    for (const Tiling& t : {Tiling::geodetic(), Tiling::webmercator()}) {
      WorldFrame w(t, 256, 10, surface);
      for (const char* text : {"10,45,2500,30,60", "-179.9,60,800000,90,40", "0,0,20000000,0,0",
                               "120,-33,150,270,80"}) {
        const CameraPose p = CameraPose::parse(text);
        const CameraPose q = Orbit::from_pose(p, w, 100).pose(w, p.fov_y_deg);
        expect_same_pose(p, q,
                         std::string(text) + (surface == Surface::kGlobe ? " globe" : " flat"));
      }
    }
  }
}

TEST(Orbit, GlobePanMovesTheTargetOverTheEllipsoid) {
  WorldFrame w(Tiling::geodetic(), 256, 10, Surface::kGlobe);
  // Straight down from 10 km: the target is the point below.
  Orbit o = Orbit::from_pose(CameraPose::parse("10,45,10000,0,0"), w, 0);
  // Dragging 100 px up at 1000 px per radian takes the view 1 km north
  // (heading 0: screen up is north).
  o.pan(0, -100, 1000, w);
  const CameraPose p = o.pose(w, 45);
  const double m_per_deg_lat = globe::viewer::wgs84::kA * (1 - globe::viewer::wgs84::kE2) /
                               std::pow(1 - globe::viewer::wgs84::kE2 * 0.5, 1.5) *
                               std::numbers::pi / 180;
  EXPECT_NEAR((p.lat - 45) * m_per_deg_lat, 1000, 10);
  EXPECT_NEAR(p.lon, 10, 1e-9);
  EXPECT_NEAR(p.height_m, 10000, 1);
}

TEST(Orbit, GlobeZoomTowardsAPointMovesTheTargetTowardsIt) {
  WorldFrame w(Tiling::geodetic(), 256, 10, Surface::kGlobe);
  const CameraPose start = CameraPose::parse("10,45,100000,0,0");
  Orbit o = Orbit::from_pose(start, w, 0);
  View v = make_view(start, w, 640, 480, 0, 0);
  // A ground point 1 degree east of the target.
  const glm::dvec3 east =
      w.key_to_world(w.crs_to_key(11, 45).x, w.crs_to_key(11, 45).y, 0, v.origin);
  o.zoom(0.5, w, &v, &east);
  const CameraPose p = o.pose(w, 45);
  EXPECT_NEAR(p.lon, 10.5, 1e-3);
  EXPECT_NEAR(p.lat, 45, 0.01);
  EXPECT_NEAR(o.distance_m(), 50000, 1e-6);
}

TEST(Orbit, GlobePosesAreValidOverThePolesAndTheAntimeridian) {
  WorldFrame w(Tiling::webmercator(), 256, 10, Surface::kGlobe);
  for (const char* text : {"0,89.9,3000000,0,30", "180,0,500000,90,70", "-180,-89,10000,0,85"}) {
    Orbit o = Orbit::from_pose(CameraPose::parse(text), w, 0);
    for (int i = 0; i < 8; ++i) {
      o.turn(45, 0);
      o.pan(50, -30, 800, w);
      const CameraPose p = o.pose(w, 45);
      EXPECT_TRUE(std::isfinite(p.lon) && std::isfinite(p.lat) && std::isfinite(p.height_m))
          << text;
      EXPECT_GE(p.lat, -90);
      EXPECT_LE(p.lat, 90);
      EXPECT_GE(p.pitch_deg, 0);
      EXPECT_LE(p.pitch_deg, 89.9);
      EXPECT_NO_THROW(CameraPose::parse(p.str())) << p.str();
    }
  }
}

}  // namespace
