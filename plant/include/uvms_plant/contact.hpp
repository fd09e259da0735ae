// SPDX-License-Identifier: Apache-2.0
// contact.hpp: contact monitoring of the truth model (SPEC §5): links as capsules, the hull as
// a box, scene obstacles (the vent chimney) as cylinders. Contact is not simulated: the plant
// asks ContactMonitor::Check every tick for the closest checked pair and ends the run when it
// touches, penetrates, or comes closer than the configured clearance.
//
// How distances are computed (libccd 2.1 has no separation-distance query: its public API is
// ccdGJKIntersect, ccdGJKSeparate, ccdGJKPenetration, ccdMPRIntersect, ccdMPRPenetration, all
// of which answer only "do they intersect" and "how deep"):
//  - every shape is a convex "core" swept by a sphere of radius r: a capsule is a segment swept
//    by its radius, a box and a cylinder are their own cores (r = 0);
//  - separated cores: a GJK distance iteration (Gilbert, Johnson, Keerthi 1988) on the cores'
//    support functions, bounded by kGjkMaxIterations; signed distance = core distance − r_a − r_b,
//    which stays exact when only the swept radii overlap;
//  - intersecting cores: libccd's GJK+EPA (ccdGJKPenetration) on the full shapes with the
//    same support functions gives the penetration depth, reported as a negative distance
//    (ccdMPRPenetration when EPA fails or claims ~0 depth, a known libccd 2.1 weakness);
//  - capsule–capsule pairs in ContactMonitor take the closed-form segment–segment distance as
//    an exact fast path (the tests check the general path and libccd against it).
#pragma once

#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "uvms_plant/params.hpp"

namespace uvms::plant {

/// A segment a–b swept by a sphere of radius radius_m (an arm link). a == b is a sphere.
/// Inertial frame [m].
struct Capsule {
  Vec3 a{Vec3::Zero()};
  Vec3 b{Vec3::Zero()};
  double radius_m{0.0};
};

/// An oriented box (the vehicle hull): center, orientation R (box axes → inertial, columns
/// are the box axes), half edge lengths along the box axes. Inertial frame [m].
struct Box {
  Vec3 center_m{Vec3::Zero()};
  Mat3 R{Mat3::Identity()};
  Vec3 half_extent_m{Vec3::Zero()};
};

/// A solid right circular cylinder (the vent chimney: axis = +z): the disk of radius radius_m
/// centred on base_center_m, perpendicular to the unit vector axis, swept height_m along
/// axis. Inertial frame [m].
struct Cylinder {
  Vec3 base_center_m{Vec3::Zero()};
  Vec3 axis{Vec3::UnitZ()};  ///< unit vector [-]
  double height_m{0.0};
  double radius_m{0.0};
};

using Shape = std::variant<Capsule, Box, Cylinder>;

/// A named body of the scene. Pairs of bodies with the same group >= 0 are never checked
/// (e.g. the parts of one rigid body); group < 0 means "no group".
struct Body {
  std::string name;
  Shape shape{Capsule{}};
  int group{-1};
};

/// Indices of two bodies in the vector given to ContactMonitor::Check, i < j.
struct ContactPair {
  std::size_t i{0};
  std::size_t j{0};
};

/// How ShapeDistance obtained its answer.
enum class DistanceMethod {
  kGjk,            ///< own GJK distance between separated cores, minus the radii
  kLibccdEpa,      ///< cores intersect: −depth from libccd ccdGJKPenetration (EPA)
  kLibccdMpr,      ///< cores intersect, EPA failed or claimed ~0 depth: −depth from
                   ///< ccdMPRPenetration (an upper bound on the depth)
  kTouching,       ///< cores intersect but libccd found no penetration: touching contact
  kClosedForm,     ///< capsule–capsule segment distance (ContactMonitor's fast path)
};

/// Signed distance between two shapes and how it was found.
struct DistanceResult {
  double distance_m{0.0};  ///< > 0 separated, <= 0 touching or penetrating (−depth) [m]
  Vec3 point_a_m{Vec3::Zero()};  ///< closest point on a; unspecified when the cores meet [m]
  Vec3 point_b_m{Vec3::Zero()};  ///< closest point on b; unspecified when the cores meet [m]
  DistanceMethod method{DistanceMethod::kGjk};
  int gjk_iterations{0};   ///< support-point evaluations of the GJK distance loop
  bool converged{true};    ///< false: GJK hit kGjkMaxIterations; distance_m is then its
                           ///< lower bound (conservative for a monitor)
};

/// Iteration bound of the GJK distance loop and of libccd's GJK (ccd_t::max_iterations).
constexpr int kGjkMaxIterations = 64;
/// The GJK distance stops when its upper and lower bounds differ by less than
/// max(kGjkAbsTol_m, kGjkRelTol·distance).
constexpr double kGjkAbsTol_m = 1e-10;
constexpr double kGjkRelTol = 1e-10;
/// Cores closer than this count as intersecting and go to libccd's penetration query [m].
constexpr double kCoreContactTol_m = 1e-9;

/// Closest distance between segments p1–q1 and p2–q2 (closed form, exact up to rounding),
/// optionally the closest points c1 on the first and c2 on the second segment. Inputs [m].
double SegmentSegmentDistance(const Vec3 &p1, const Vec3 &q1, const Vec3 &p2, const Vec3 &q2,
                              Vec3 *c1 = nullptr, Vec3 *c2 = nullptr);

/// Closed-form capsule–capsule separation: segment distance − r_a − r_b [m]. Negative when
/// the swept radii overlap; equals the penetration depth (negated) while the segments do not
/// intersect. Shapes are not validated.
double CapsuleCapsuleDistance(const Capsule &a, const Capsule &b);

/// Signed distance between any two shapes by the general path (GJK on the cores, libccd
/// penetration when the cores intersect); no closed-form shortcut. Throws
/// std::invalid_argument for invalid dimensions (negative radius, height or half extent;
/// cylinder axis not unit; box R not a rotation). Non-finite coordinates give a NaN distance.
DistanceResult ShapeDistance(const Shape &a, const Shape &b);

/// libccd primitives on the same support functions, exposed so that tests can check the
/// monitor's GJK against an independent implementation. Shapes as for ShapeDistance.
/// ccdGJKIntersect (true: the shapes intersect or touch within libccd's tolerance).
bool LibccdIntersect(const Shape &a, const Shape &b);
/// Penetration depth of b into a [m] by ccdGJKPenetration (use_mpr false: GJK+EPA) or
/// ccdMPRPenetration (use_mpr true); std::nullopt when libccd finds no intersection.
std::optional<double> LibccdPenetrationDepth(const Shape &a, const Shape &b, bool use_mpr);
/// Separation distance [m] from libccd alone: the smallest r for which a and b swept by a
/// sphere of radius r intersect (ccdGJKIntersect), found by bisection to tol_m. 0 when they
/// already intersect. Slow (~60 libccd calls): a cross-check, not the monitor's path.
double LibccdBisectionDistance(const Shape &a, const Shape &b, double tol_m = 1e-9);

/// Checks every pair of bodies except pairs inside one group (group >= 0) and pairs whose
/// names are listed as ignored (adjacent links touching at their joint, the first link and
/// the hull at the arm base: the caller lists those, in either order).
class ContactMonitor {
 public:
  /// Result of one Check. Check is const and keeps no state: safe to call concurrently.
  struct Report {
    double min_distance_m{0.0};  ///< smallest signed distance over the checked pairs [m];
                                 ///< +inf when no pair is checked, NaN on non-finite input
    std::string body_a, body_b;  ///< names of the closest pair (empty when none)
    bool breach{false};          ///< min_distance_m < clearance, or <= 0 (contact), or NaN
    ContactPair pair{};          ///< indices of the closest pair in the bodies vector
    DistanceMethod method{DistanceMethod::kGjk};  ///< how the closest pair's distance was found
  };

  /// clearance_m: a finite distance >= 0 [m]; closer than this is a breach. ignore_pairs:
  /// unordered pairs of body names never checked. Throws std::invalid_argument on a bad
  /// clearance.
  ContactMonitor(double clearance_m, std::vector<std::pair<std::string, std::string>> ignore_pairs);

  /// The closest checked pair of bodies (inertial-frame shapes). Pairs are visited in order
  /// of a lower bound on their distance (bounding spheres and axis-aligned boxes) and
  /// skipped once that bound reaches the best distance found: only the closest pair's
  /// distance is computed exactly; the others are only known to be larger. Static scene
  /// bodies that touch each other (a chimney on the seabed) belong in one group, or every
  /// Check pays a penetration query for them and reports them. Throws std::invalid_argument for invalid shape dimensions
  /// (see ShapeDistance) naming the body; a body with non-finite coordinates makes the
  /// report NaN with a breach, naming the first checked pair that contains it.
  Report Check(const std::vector<Body> &bodies) const;

  /// The same with the checked pairs given: pairs must be CheckedPairs(bodies), computed once
  /// by a caller that moves the same bodies every tick (the pair rule reads names and groups
  /// only, so the list stays valid while they do not change).
  Report Check(const std::vector<Body> &bodies, const std::vector<ContactPair> &pairs) const;

  /// Whether the pair of bodies a, b is checked by the rule above (symmetric).
  bool IsChecked(const Body &a, const Body &b) const;

  /// Every checked pair of bodies, i < j, in lexicographic order.
  std::vector<ContactPair> CheckedPairs(const std::vector<Body> &bodies) const;

  double clearance_m() const { return clearance_m_; }

 private:
  double clearance_m_{0.0};
  std::set<std::pair<std::string, std::string>> ignore_;  ///< stored as (min, max) names
};

}  // namespace uvms::plant
