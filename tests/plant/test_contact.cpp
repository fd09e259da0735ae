// SPDX-License-Identifier: Apache-2.0
// test_contact.cpp: shapes, signed distances and the contact monitor (SPEC §5). Expected
// values come from the geometry (derivations in the comments); the general path (GJK on the
// cores + libccd EPA) and a libccd-only distance (bisection on a swept sphere with
// ccdGJKIntersect) are checked against the closed-form segment distance.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "uvms_plant/contact.hpp"

using namespace uvms::plant;

namespace {

// The GJK distance between polytope or segment cores terminates on an exact face; its
// stopping gap is kGjkAbsTol_m = 1e-10 m. Curved cores (cylinders) converge to the same gap.
constexpr double kGjkTol_m = 1e-8;
// libccd 2.1's GJK boolean gives up ("no intersection") when its unnormalised search
// direction |AB × AO × AB|², of order |AB|⁴·dist², falls below DBL_EPSILON: with simplex
// edges of ~0.1 m that is dist ≲ 1e-6 m, and the bisection oracle overestimates by up to a
// few 1e-5 m (measured: 6.9e-6 m here, 3.4e-5 m with another first direction). Its
// tolerance is set from that, not from ours.
constexpr double kBisectTol_m = 1e-4;
// libccd EPA with epa_tolerance 1e-12 m²: polytope pairs exact, swept shapes to ~1e-6 m.
constexpr double kEpaTol_m = 1e-5;

Box UnitCube(const Vec3 &center) {  // edge 1 m, axis-aligned
  return Box{center, Mat3::Identity(), Vec3(0.5, 0.5, 0.5)};
}

Mat3 Rz(double angle_rad) { return Eigen::AngleAxisd(angle_rad, Vec3::UnitZ()).toRotationMatrix(); }

// Every way this project computes one separated distance agrees with the expected value.
void CheckAllPaths(const Shape &a, const Shape &b, double expected_m) {
  const DistanceResult g = ShapeDistance(a, b);
  CHECK(g.converged);
  CHECK(g.method == DistanceMethod::kGjk);
  CHECK(g.distance_m == Approx(expected_m).margin(kGjkTol_m));
  // The witness points are that far apart.
  CHECK((g.point_b_m - g.point_a_m).norm() == Approx(expected_m).margin(kGjkTol_m));
  // Symmetric in its arguments.
  CHECK(ShapeDistance(b, a).distance_m == Approx(expected_m).margin(kGjkTol_m));
  CHECK(LibccdBisectionDistance(a, b) == Approx(expected_m).margin(kBisectTol_m));
  CHECK_FALSE(LibccdIntersect(a, b));
  // The monitor sees the same distance (closed form for two capsules).
  const ContactMonitor mon(0.0, {});
  const auto rep = mon.Check({Body{"a", a, -1}, Body{"b", b, -1}});
  CHECK(rep.min_distance_m == Approx(expected_m).margin(kGjkTol_m));
  CHECK(rep.body_a == "a");
  CHECK(rep.body_b == "b");
  CHECK_FALSE(rep.breach);
}

}  // namespace

TEST_CASE("CapsuleCapsuleParallelSegmentsMatchClosedForm", "[contact]") {
  // Overlapping parallel segments along x, offset 0.3 m in y: segment distance 0.3 m,
  // radii 0.05 + 0.05 → 0.2 m.
  const Capsule a{Vec3(0, 0, 0), Vec3(1, 0, 0), 0.05};
  const Capsule b{Vec3(0.5, 0.3, 0), Vec3(1.5, 0.3, 0), 0.05};
  constexpr double kOverlapping_m = 0.3 - 0.1;
  CHECK(SegmentSegmentDistance(a.a, a.b, b.a, b.b) == Approx(0.3).margin(1e-15));
  CHECK(CapsuleCapsuleDistance(a, b) == Approx(kOverlapping_m).margin(1e-15));
  CheckAllPaths(a, b, kOverlapping_m);
  // Parallel, not overlapping along x: closest endpoints (1,0,0)–(2,0.3,0),
  // √(1² + 0.3²) − 0.1.
  const Capsule c{Vec3(2, 0.3, 0), Vec3(3, 0.3, 0), 0.05};
  const double kDisjoint_m = std::sqrt(1.0 + 0.09) - 0.1;
  CHECK(CapsuleCapsuleDistance(a, c) == Approx(kDisjoint_m).margin(1e-15));
  CheckAllPaths(a, c, kDisjoint_m);
}

TEST_CASE("CapsuleCapsuleSkewSegmentsMatchClosedForm", "[contact]") {
  // Segment along x in z = 0 and one along (1,1,0)/√2 in z = 0.5, their projections
  // crossing inside both: the common normal is z, segment distance 0.5 m. Radii 0.1 + 0.15.
  const Capsule a{Vec3(-1, 0, 0), Vec3(1, 0, 0), 0.1};
  const Capsule b{Vec3(-0.6, -0.7, 0.5), Vec3(0.8, 0.7, 0.5), 0.15};
  constexpr double kExpected_m = 0.5 - 0.25;
  Vec3 ca, cb;
  CHECK(SegmentSegmentDistance(a.a, a.b, b.a, b.b, &ca, &cb) == Approx(0.5).margin(1e-15));
  // b crosses y = 0 at x = −0.6 + 0.7 = 0.1: the closest points are (0.1,0,0), (0.1,0,0.5).
  CHECK((ca - Vec3(0.1, 0, 0)).norm() < 1e-12);
  CHECK((cb - Vec3(0.1, 0, 0.5)).norm() < 1e-12);
  CheckAllPaths(a, b, kExpected_m);
  // Skew lines whose closest points fall outside b: b ends at y = −0.2 before reaching the
  // line of a: its endpoint (0.5,−0.2,0.5) against a's segment: √(0.2² + 0.5²).
  const Capsule c{Vec3(0.5, -1, 0.5), Vec3(0.5, -0.2, 0.5), 0.0};
  const double kEndpoint_m = std::sqrt(0.04 + 0.25) - 0.1;
  CHECK(CapsuleCapsuleDistance(a, c) == Approx(kEndpoint_m).margin(1e-15));
  CheckAllPaths(a, c, kEndpoint_m);
}

TEST_CASE("CapsuleCapsuleCollinearSegmentsMatchClosedForm", "[contact]") {
  // Collinear on x, gap from x = 1 to x = 1.5: 0.5 m, radii 0.1 + 0.1.
  const Capsule a{Vec3(0, 0, 0), Vec3(1, 0, 0), 0.1};
  const Capsule b{Vec3(1.5, 0, 0), Vec3(3, 0, 0), 0.1};
  CHECK(CapsuleCapsuleDistance(a, b) == Approx(0.3).margin(1e-15));
  CheckAllPaths(a, b, 0.3);
  // Degenerate segments: two spheres 2 m apart, radii 0.25 + 0.5.
  const Capsule s1{Vec3(1, 1, 1), Vec3(1, 1, 1), 0.25};
  const Capsule s2{Vec3(1, 1, 3), Vec3(1, 1, 3), 0.5};
  CheckAllPaths(s1, s2, 1.25);
  // Collinear and overlapping by 0.5 m: the segments meet, so the general path asks libccd's
  // EPA. Sliding apart along x takes 0.5 + 0.2 m, sideways only r_a + r_b = 0.2 m: depth 0.2.
  const Capsule c{Vec3(0.5, 0, 0), Vec3(2, 0, 0), 0.1};
  const DistanceResult d = ShapeDistance(a, c);
  CHECK(d.method == DistanceMethod::kLibccdEpa);
  CHECK(d.distance_m == Approx(-0.2).margin(kEpaTol_m));
}

TEST_CASE("CapsuleBoxDistancesMatchHandGeometry", "[contact]") {
  const Box cube = UnitCube(Vec3::Zero());  // faces at ±0.5 m
  // Above the top face: horizontal capsule at z = 0.8, radius 0.1: 0.8 − 0.5 − 0.1.
  CheckAllPaths(Capsule{Vec3(-0.2, 0, 0.8), Vec3(0.2, 0, 0.8), 0.1}, cube, 0.2);
  // Beside the edge {x = 0.5, z = 0.5} (along y), parallel to it at x = 0.8, z = 0.9:
  // √(0.3² + 0.4²) = 0.5 to the edge, minus the radius 0.1.
  CheckAllPaths(Capsule{Vec3(0.8, -0.2, 0.9), Vec3(0.8, 0.2, 0.9), 0.1}, cube, 0.4);
  // Off the corner (0.5,0.5,0.5): the near end is at corner + (0.1,0.2,0.2), 0.3 m away, and
  // the segment points further away along (1,2,2)/3: 0.3 − 0.05.
  const Vec3 near = Vec3(0.6, 0.7, 0.7);
  CheckAllPaths(Capsule{near, near + 0.5 * Vec3(1, 2, 2) / 3.0, 0.05}, cube, 0.25);
  // A box turned 30° about z, capsule on its local +x axis 1 m from the center: 1 − 0.5 − 0.1.
  const Box turned{Vec3(1, 2, 0), Rz(M_PI / 6), Vec3(0.5, 0.5, 0.5)};
  const Vec3 ex = turned.R.col(0), ez = turned.R.col(2);
  CheckAllPaths(Capsule{turned.center_m + ex - 0.2 * ez, turned.center_m + ex + 0.2 * ez, 0.1},
                turned, 0.4);
}

TEST_CASE("BoxBoxDistancesMatchHandGeometry", "[contact]") {
  // Separated along x: faces at x = 0.5 and x = 2 − 0.3, y and z projections overlapping.
  const Box a = UnitCube(Vec3::Zero());
  const Box b{Vec3(2, 0.1, -0.2), Mat3::Identity(), Vec3(0.3, 0.3, 0.3)};
  CheckAllPaths(a, b, 2.0 - 0.5 - 0.3);
  // A unit cube turned 45° about z at x = 2: its vertical edge reaches x = 2 − 0.5·√2.
  const Box c{Vec3(2, 0, 0), Rz(M_PI / 4), Vec3(0.5, 0.5, 0.5)};
  CheckAllPaths(a, c, 1.5 - 0.5 * std::sqrt(2.0));
}

TEST_CASE("CapsuleCylinderChimneySideAndTop", "[contact]") {
  // The vent chimney: vertical cylinder, base at the origin, 2 m tall, radius 0.5 m.
  const Cylinder chimney{Vec3::Zero(), Vec3::UnitZ(), 2.0, 0.5};
  // Side: vertical capsule at x = 1, radius 0.1: 1 − 0.5 − 0.1.
  CheckAllPaths(Capsule{Vec3(1, 0, 0.5), Vec3(1, 0, 1.5), 0.1}, chimney, 0.4);
  // Side, off the axes: at (0.9, 1.2) the radial distance is 1.5: 1.5 − 0.5 − 0.1.
  CheckAllPaths(Capsule{Vec3(0.9, 1.2, 0.2), Vec3(0.9, 1.2, 1.8), 0.1}, chimney, 0.9);
  // Top: horizontal capsule at z = 2.3 over the cap: 0.3 − 0.1.
  CheckAllPaths(Capsule{Vec3(-0.3, 0, 2.3), Vec3(0.3, 0, 2.3), 0.1}, chimney, 0.2);
  // Over the rim: a sphere at (0.8, 0, 2.4); nearest rim point (0.5, 0, 2), √(0.3² + 0.4²).
  CheckAllPaths(Capsule{Vec3(0.8, 0, 2.4), Vec3(0.8, 0, 2.4), 0.1}, chimney, 0.4);
  // A tilted chimney (axis (0,1,1)/√2) against a sphere on its axis beyond the top cap.
  const Vec3 u = Vec3(0, 1, 1).normalized();
  const Cylinder tilted{Vec3(1, 1, 1), u, 1.0, 0.3};
  CheckAllPaths(Capsule{Vec3(1, 1, 1) + 1.7 * u, Vec3(1, 1, 1) + 1.7 * u, 0.2}, tilted, 0.5);
}

TEST_CASE("PenetrationGivesNonPositiveDistanceAndBreach", "[contact]") {
  const ContactMonitor mon(0.05, {});
  // Two unit cubes 0.9 m apart overlap by 0.1 m along x: EPA on polytopes is exact.
  const Box a = UnitCube(Vec3::Zero());
  const Box b = UnitCube(Vec3(0.9, 0, 0));
  DistanceResult d = ShapeDistance(a, b);
  CHECK(d.method == DistanceMethod::kLibccdEpa);
  CHECK(d.distance_m == Approx(-0.1).margin(1e-9));
  auto rep = mon.Check({Body{"hull", a, -1}, Body{"crate", b, -1}});
  CHECK(rep.breach);
  CHECK(rep.min_distance_m <= 0.0);
  CHECK(rep.body_a == "hull");
  CHECK(rep.body_b == "crate");
  // A capsule poking 0.05 m into the top face with radius 0.05: lifting it by 0.1 m frees it.
  const Capsule probe{Vec3(0, 0, 0.45), Vec3(0, 0, 1.0), 0.05};
  d = ShapeDistance(probe, a);
  CHECK(d.method == DistanceMethod::kLibccdEpa);
  CHECK(d.distance_m == Approx(-0.1).margin(kEpaTol_m));
  // Capsules whose radii overlap but whose segments do not: segment distance 0.15, radii
  // 0.1 + 0.1: depth 0.05 by the closed form, by GJK on the cores, and by libccd's EPA and MPR
  // on the full capsules.
  const Capsule c1{Vec3(0, 0, 0), Vec3(1, 0, 0), 0.1};
  const Capsule c2{Vec3(0.5, -0.5, 0.15), Vec3(0.5, 0.5, 0.15), 0.1};
  CHECK(CapsuleCapsuleDistance(c1, c2) == Approx(-0.05).margin(1e-15));
  CHECK(ShapeDistance(c1, c2).distance_m == Approx(-0.05).margin(kGjkTol_m));
  CHECK(LibccdPenetrationDepth(c1, c2, false).value() == Approx(0.05).margin(kEpaTol_m));
  CHECK(LibccdPenetrationDepth(c1, c2, true).value() == Approx(0.05).margin(kEpaTol_m));
  rep = mon.Check({Body{"link3", c1, -1}, Body{"link5", c2, -1}});
  CHECK(rep.breach);
  CHECK(rep.min_distance_m == Approx(-0.05).margin(1e-12));
  CHECK(rep.method == DistanceMethod::kClosedForm);
  // danfis/libccd#25: cubes of edge 2 stacked 1.9 apart made 2.1's EPA report depth 0 with
  // the default first direction. Depth 0.1 here.
  const Box low{Vec3::Zero(), Mat3::Identity(), Vec3::Ones()};
  const Box high{Vec3(0, 0, 1.9), Mat3::Identity(), Vec3::Ones()};
  CHECK(ShapeDistance(low, high).distance_m == Approx(-0.1).margin(1e-9));
  CHECK(LibccdPenetrationDepth(low, high, false).value() == Approx(0.1).margin(1e-9));
  CHECK(LibccdPenetrationDepth(low, high, true).value() == Approx(0.1).margin(1e-9));
  // A capsule through the chimney wall (radius 0.5): its inner end is at radius 0.4, the
  // rest outside along +x, so pushing it out radially by 0.1 + 0.05 frees it (sideways needs
  // the chord half-width √(0.5² − 0.4²) + 0.05 = 0.35, up 1.05). EPA on the curved wall
  // approximates from inside: within 1e-4 m.
  const Cylinder chimney{Vec3::Zero(), Vec3::UnitZ(), 2.0, 0.5};
  d = ShapeDistance(Capsule{Vec3(0.4, 0, 1), Vec3(1.5, 0, 1), 0.05}, chimney);
  CHECK(d.distance_m <= 0.0);
  CHECK(d.distance_m == Approx(-0.15).margin(1e-4));
  // Exactly touching faces with clearance 0: a contact, hence a breach.
  const ContactMonitor touch(0.0, {});
  rep = touch.Check({Body{"a", a, -1}, Body{"b", UnitCube(Vec3(1, 0, 0)), -1}});
  CHECK(rep.min_distance_m == Approx(0.0).margin(1e-9));
  CHECK(rep.breach);
}

TEST_CASE("ClearanceThresholdSemantics", "[contact]") {
  // Cube faces at x = 0.5 and x = c − 0.5: gap = c − 1. Clearance 0.1 m.
  constexpr double kClearance_m = 0.1;
  const ContactMonitor mon(kClearance_m, {});
  const Box a = UnitCube(Vec3::Zero());
  for (const double offset_m : {1e-6, -1e-6, 1e-3, -1e-3}) {
    const double gap_m = kClearance_m + offset_m;
    const auto rep = mon.Check({Body{"a", a, -1}, Body{"b", UnitCube(Vec3(1 + gap_m, 0, 0)), -1}});
    INFO("gap " << gap_m);
    CHECK(rep.min_distance_m == Approx(gap_m).margin(1e-9));
    CHECK(rep.breach == (offset_m < 0.0));
  }
  // No checked pair: +inf, no breach.
  const auto none = mon.Check({Body{"a", a, -1}});
  CHECK(std::isinf(none.min_distance_m));
  CHECK_FALSE(none.breach);
  CHECK(none.body_a.empty());
  CHECK_THROWS_AS(ContactMonitor(-0.1, {}), std::invalid_argument);
  CHECK_THROWS_AS(ContactMonitor(std::nan(""), {}), std::invalid_argument);
}

TEST_CASE("IgnoredAndSameGroupPairsAreNotReported", "[contact]") {
  // Hull cube at the origin; a sensor pod overlapping it in the same group; link1 starting
  // inside the hull (arm base) with the pair ignored, listed in reverse order; link2 joined
  // to link1 (ignored); the chimney (radius 0.3 m, axis at x = 2). Every overlap is excluded:
  // the closest checked pair is link2 (tip at x = 1.6, radius 0.05) against the chimney
  // surface at x = 1.7: 0.1 − 0.05. (Next: pod corner (0.3,0,−0.2) to link1's start
  // (0.4,0,0): √0.05 − 0.05 ≈ 0.17.)
  const std::vector<Body> bodies{
      {"hull", UnitCube(Vec3::Zero()), 0},
      {"pod", Box{Vec3(0, 0, -0.5), Mat3::Identity(), Vec3(0.3, 0.3, 0.3)}, 0},
      {"link1", Capsule{Vec3(0.4, 0, 0), Vec3(0.9, 0, 0), 0.05}, -1},
      {"link2", Capsule{Vec3(0.9, 0, 0), Vec3(1.6, 0, 0), 0.05}, -1},
      {"chimney", Cylinder{Vec3(2, 0, -1), Vec3::UnitZ(), 2.0, 0.3}, -1},
  };
  const ContactMonitor mon(0.01, {{"hull", "link1"}, {"link2", "link1"}});
  const auto rep = mon.Check(bodies);
  CHECK(rep.min_distance_m == Approx(0.05).margin(kGjkTol_m));
  CHECK(rep.body_a == "link2");
  CHECK(rep.body_b == "chimney");
  CHECK_FALSE(rep.breach);
  // 10 pairs − hull/pod (group) − hull/link1 − link1/link2 (ignored) = 7 checked.
  CHECK(mon.CheckedPairs(bodies).size() == 7);
  CHECK_FALSE(mon.IsChecked(bodies[0], bodies[1]));
  CHECK_FALSE(mon.IsChecked(bodies[2], bodies[0]));
  CHECK(mon.IsChecked(bodies[1], bodies[2]));  // pod/link1: neither grouped nor ignored
  // The same scene without the ignore list reports an overlap.
  const ContactMonitor strict(0.01, {});
  const auto all = strict.Check(bodies);
  CHECK(all.breach);
  CHECK(all.min_distance_m <= 0.0);
  // Ungrouped (group −1) bodies are checked even when both are −1.
  auto ungrouped = bodies;
  ungrouped[0].group = -1;
  ungrouped[1].group = -1;
  CHECK(mon.CheckedPairs(ungrouped).size() == 8);
}

TEST_CASE("ClosestPairIsNamedAmongSeveralBodies", "[contact]") {
  // Five spheres on the x axis (radius 0.1) with gaps 0.5, 0.3, 0.7, 0.2 between surfaces,
  // a cube and the chimney far away: the closest pair is s3–s4, 0.2 m.
  std::vector<Body> bodies;
  double x = 0.0;
  const double gaps[] = {0.5, 0.3, 0.7, 0.2};
  for (int k = 0; k < 5; ++k) {
    const Vec3 c(x, 0, 0);
    bodies.push_back(Body{"s" + std::to_string(k), Capsule{c, c, 0.1}, -1});
    if (k < 4) x += 0.2 + gaps[k];
  }
  bodies.push_back(Body{"cube", UnitCube(Vec3(0, 5, 0)), -1});
  bodies.push_back(Body{"chimney", Cylinder{Vec3(0, -5, -1), Vec3::UnitZ(), 2.0, 0.5}, -1});
  const ContactMonitor mon(0.1, {});
  const auto rep = mon.Check(bodies);
  CHECK(rep.min_distance_m == Approx(0.2).margin(1e-12));
  CHECK(rep.body_a == "s3");
  CHECK(rep.body_b == "s4");
  CHECK(rep.pair.i == 3);
  CHECK(rep.pair.j == 4);
}

TEST_CASE("MonitorMinimumEqualsBruteForceOverRandomScenes", "[contact]") {
  // The monitor prunes pairs by bounding spheres: its minimum must still equal the minimum
  // of ShapeDistance over every checked pair. 12 bodies per scene (7 links, hull, chimney,
  // 3 boxes), 50 scenes, fixed seed.
  std::mt19937_64 rng(20261101);
  std::uniform_real_distribution<double> pos(-1.5, 1.5), unit(-1.0, 1.0), len(0.05, 0.4);
  const ContactMonitor mon(0.05, {});
  for (int scene = 0; scene < 50; ++scene) {
    std::vector<Body> bodies;
    for (int k = 0; k < 7; ++k) {
      const Vec3 a(pos(rng), pos(rng), pos(rng));
      const Vec3 b = a + len(rng) * Vec3(unit(rng), unit(rng), unit(rng));
      bodies.push_back(Body{"link" + std::to_string(k), Capsule{a, b, 0.0445}, -1});
    }
    for (int k = 0; k < 4; ++k) {
      const Eigen::Quaterniond q(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized());
      bodies.push_back(Body{"box" + std::to_string(k),
                            Box{Vec3(pos(rng), pos(rng), pos(rng)), q.toRotationMatrix(),
                                Vec3(len(rng), len(rng), len(rng))},
                            -1});
    }
    bodies.push_back(Body{"chimney", Cylinder{Vec3(pos(rng), pos(rng), -2), Vec3::UnitZ(), 2.5, 0.4}, -1});
    double best = std::numeric_limits<double>::infinity();
    for (const ContactPair &p : mon.CheckedPairs(bodies)) {
      const Shape &a = bodies[p.i].shape, &b = bodies[p.j].shape;
      double d = ShapeDistance(a, b).distance_m;
      if (std::holds_alternative<Capsule>(a) && std::holds_alternative<Capsule>(b) &&
          SegmentSegmentDistance(std::get<Capsule>(a).a, std::get<Capsule>(a).b,
                                 std::get<Capsule>(b).a, std::get<Capsule>(b).b) > kCoreContactTol_m) {
        d = CapsuleCapsuleDistance(std::get<Capsule>(a), std::get<Capsule>(b));
      }
      best = std::min(best, d);
    }
    const auto rep = mon.Check(bodies);
    INFO("scene " << scene);
    CHECK(rep.min_distance_m == Approx(best).margin(1e-12));
  }
}

TEST_CASE("RandomCapsulePairsLibccdAndGjkMatchClosedForm", "[contact]") {
  // 2000 random capsule pairs in a 2 m box (fixed seed): the general path (GJK on the
  // segments, minus radii) vs the closed form; every 10th pair also the libccd-only
  // bisection distance; pairs whose radii overlap while the segments stay apart also
  // libccd's EPA depth vs r_a + r_b − segment distance.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(-1.0, 1.0), rad(0.0, 0.3);
  double max_gjk_err = 0.0, max_bisect_err = 0.0, max_epa_err = 0.0;
  int n_bisect = 0, n_epa = 0, max_iter = 0;
  for (int k = 0; k < 2000; ++k) {
    const Capsule a{Vec3(pos(rng), pos(rng), pos(rng)), Vec3(pos(rng), pos(rng), pos(rng)), rad(rng)};
    const Capsule b{Vec3(pos(rng), pos(rng), pos(rng)), Vec3(pos(rng), pos(rng), pos(rng)), rad(rng)};
    const double seg = SegmentSegmentDistance(a.a, a.b, b.a, b.b);
    const double closed = seg - a.radius_m - b.radius_m;
    if (seg > 1e-6) {
      const DistanceResult g = ShapeDistance(a, b);
      REQUIRE(g.converged);
      max_iter = std::max(max_iter, g.gjk_iterations);
      max_gjk_err = std::max(max_gjk_err, std::abs(g.distance_m - closed));
      if (closed > 0.0 && k % 10 == 0) {
        max_bisect_err = std::max(max_bisect_err, std::abs(LibccdBisectionDistance(a, b) - closed));
        ++n_bisect;
      }
      if (closed < -1e-3) {
        // Penetrating with disjoint segments: depth = r_a + r_b − segment distance (the
        // minimal translation moves the segments apart along their common normal).
        const auto depth = LibccdPenetrationDepth(a, b, false);
        REQUIRE(depth.has_value());
        max_epa_err = std::max(max_epa_err, std::abs(-*depth - closed));
        ++n_epa;
        // MPR's depth is along its final portal normal: never below the minimal depth.
        const auto mpr = LibccdPenetrationDepth(a, b, true);
        REQUIRE(mpr.has_value());
        CHECK(*mpr >= -closed - kEpaTol_m);
      }
    }
  }
  INFO("max |GJK − closed| " << max_gjk_err << " m, max GJK iterations " << max_iter);
  INFO("max |libccd bisection − closed| " << max_bisect_err << " m over " << n_bisect);
  INFO("max |libccd EPA − closed| " << max_epa_err << " m over " << n_epa);
  CHECK(max_gjk_err < kGjkTol_m);
  CHECK(max_bisect_err < kBisectTol_m);
  CHECK(max_epa_err < kEpaTol_m);
  CHECK(n_bisect > 20);
  CHECK(n_epa > 20);
  WARN("max |GJK - closed| " << max_gjk_err << " m (max " << max_iter << " iterations); "
       "libccd bisection " << max_bisect_err << " m (" << n_bisect << " pairs); libccd EPA "
       << max_epa_err << " m (" << n_epa << " pairs)");
}

TEST_CASE("RandomSpheresMatchPointDistanceToBoxAndCylinder", "[contact]") {
  // A sphere is a capsule with a == b; its distance to a convex solid is the distance of its
  // center to the solid minus its radius, in closed form for both:
  //  box: with x the center in box axes, |x − clamp(x, −h, h)|;
  //  cylinder: with ρ the radial and z the axial coordinate from the base center,
  //  √(max(ρ − R, 0)² + max(z − H, −z, 0)²).
  // 1000 spheres around a turned box and a tilted cylinder (fixed seed), centers outside.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> pos(-2.0, 2.0), rad(0.0, 0.2);
  const Box box{Vec3(0.1, -0.2, 0.3), Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix(),
                Vec3(0.6, 0.3, 0.45)};
  const Vec3 axis = Vec3(0.2, -0.3, 1.0).normalized();
  const Cylinder cyl{Vec3(-0.2, 0.1, -0.8), axis, 1.6, 0.5};
  double max_box_err = 0.0, max_cyl_err = 0.0;
  int max_iter = 0, n_box = 0, n_cyl = 0;
  for (int k = 0; k < 1000; ++k) {
    const Vec3 c(pos(rng), pos(rng), pos(rng));
    const double r = rad(rng);
    const Capsule sphere{c, c, r};
    const Vec3 x = box.R.transpose() * (c - box.center_m);
    const double box_d = (x - x.cwiseMax(-box.half_extent_m).cwiseMin(box.half_extent_m)).norm();
    if (box_d > 1e-3) {
      const DistanceResult g = ShapeDistance(sphere, box);
      REQUIRE(g.converged);
      max_box_err = std::max(max_box_err, std::abs(g.distance_m - (box_d - r)));
      max_iter = std::max(max_iter, g.gjk_iterations);
      ++n_box;
    }
    const double z = (c - cyl.base_center_m).dot(axis);
    const double rho = ((c - cyl.base_center_m) - z * axis).norm();
    const double dz = std::max({z - cyl.height_m, -z, 0.0});
    const double cyl_d = std::hypot(std::max(rho - cyl.radius_m, 0.0), dz);
    if (cyl_d > 1e-3) {
      const DistanceResult g = ShapeDistance(sphere, cyl);
      REQUIRE(g.converged);
      max_cyl_err = std::max(max_cyl_err, std::abs(g.distance_m - (cyl_d - r)));
      max_iter = std::max(max_iter, g.gjk_iterations);
      ++n_cyl;
    }
  }
  INFO("max error box " << max_box_err << " m (" << n_box << "), cylinder " << max_cyl_err
       << " m (" << n_cyl << "), max GJK iterations " << max_iter);
  CHECK(max_box_err < kGjkTol_m);
  CHECK(max_cyl_err < kGjkTol_m);
  CHECK(max_iter < kGjkMaxIterations);
  CHECK(n_box > 500);
  CHECK(n_cyl > 500);
  WARN("sphere-box max error " << max_box_err << " m, sphere-cylinder " << max_cyl_err
       << " m, max GJK iterations " << max_iter);
}

TEST_CASE("InvalidShapesThrowAndNonFiniteCoordinatesBreach", "[contact]") {
  const ContactMonitor mon(0.1, {});
  const Box cube = UnitCube(Vec3::Zero());
  CHECK_THROWS_AS(mon.Check({Body{"bad", Capsule{Vec3::Zero(), Vec3::UnitX(), -0.1}, -1},
                             Body{"cube", cube, -1}}),
                  std::invalid_argument);
  CHECK_THROWS_AS(ShapeDistance(Cylinder{Vec3::Zero(), Vec3(0, 0, 2), 1.0, 0.5}, cube),
                  std::invalid_argument);
  CHECK_THROWS_AS(ShapeDistance(Box{Vec3::Zero(), 2.0 * Mat3::Identity(), Vec3::Ones()}, cube),
                  std::invalid_argument);
  // A NaN link (a diverged state) ends the run as a breach naming the pair.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto rep = mon.Check({Body{"cube", UnitCube(Vec3(5, 0, 0)), -1},
                              Body{"link4", Capsule{Vec3(nan, 0, 0), Vec3::UnitX(), 0.05}, -1}});
  CHECK(std::isnan(rep.min_distance_m));
  CHECK(rep.breach);
  CHECK(rep.body_a == "cube");
  CHECK(rep.body_b == "link4");
  CHECK(std::isnan(ShapeDistance(Capsule{Vec3(1e9, 0, 0), Vec3::Zero(), 0.1}, cube).distance_m));
}
