// SPDX-License-Identifier: Apache-2.0
// contact.cpp: shapes, signed distances and the contact monitor (SPEC §5). See contact.hpp
// for the method; libccd 2.1 answers intersection and penetration only, so the separation
// distance comes from a GJK distance loop written here on the same support functions.
#include "uvms_plant/contact.hpp"

#include <ccd/ccd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>

namespace uvms::plant {

namespace {

/// Coordinates beyond this are treated like non-finite ones (a diverged state, not a scene):
/// they would overflow the squared norms inside GJK and libccd [m].
constexpr double kMaxCoordinate_m = 1e6;
/// Budget of libccd support-function calls per query. libccd 2.1 bounds its GJK loop by
/// ccd_t::max_iterations, but its EPA and MPR loops only by their tolerances: past this
/// budget the support functions return the origin for both shapes, which ends any of those
/// loops at its next tolerance test (the answer is then the current, inner estimate).
constexpr long kLibccdSupportBudget = 4096;
/// libccd tolerances. EPA stops when a new support point gains less than epa_tolerance in
/// (gain · depth) [m²] or lies closer than sqrt(epa_tolerance) to the nearest face: 1e-12
/// gives depths to ~1e-6 m. MPR's tolerance is a distance [m].
constexpr double kEpaTolerance_m2 = 1e-12;
constexpr double kMprTolerance_m = 1e-9;
/// Cores whose Gram matrix is this close to singular (relative) are degenerate sub-simplices.
constexpr double kDegenerateGram = 1e-13;

enum class CoreKind { kSegment, kBox, kCylinder };

/// A shape as its convex core swept by a sphere of radius sweep_m: the form both the GJK
/// distance and the libccd callbacks read. A plain struct: libccd gets a pointer to it.
struct Convex {
  CoreKind kind{CoreKind::kSegment};
  Vec3 p0{Vec3::Zero()};       ///< segment start; cylinder base center [m]
  Vec3 p1{Vec3::Zero()};       ///< segment end; cylinder top center [m]
  Mat3 R{Mat3::Identity()};    ///< box axes (columns) [-]
  Vec3 half{Vec3::Zero()};     ///< box half extents [m]
  Vec3 axis{Vec3::UnitZ()};    ///< cylinder unit axis [-]
  double disk_radius_m{0.0};   ///< cylinder radius [m]
  double sweep_m{0.0};         ///< capsule radius, 0 for box and cylinder [m]
  Vec3 center{Vec3::Zero()};   ///< a point of the core (segment midpoint, box/cylinder center) [m]
  double bound_m{0.0};         ///< radius of a sphere about center containing the shape [m]
  Vec3 box_lo{Vec3::Zero()};   ///< axis-aligned bounding box of the shape, inertial [m]
  Vec3 box_hi{Vec3::Zero()};
  bool finite{true};           ///< every coordinate finite and within kMaxCoordinate_m
};

bool Sane(const Vec3 &v) { return v.allFinite() && v.cwiseAbs().maxCoeff() <= kMaxCoordinate_m; }

void RequireDimension(double x, const char *what, const std::string &who) {
  if (!std::isfinite(x) || x < 0.0 || x > kMaxCoordinate_m) {
    throw std::invalid_argument("contact: body '" + who + "': " + what +
                                " must be finite and >= 0");
  }
}

/// Validates dimensions (throws std::invalid_argument naming the body) and converts.
Convex MakeConvex(const Shape &shape, const std::string &who) {
  Convex c;
  if (const auto *cap = std::get_if<Capsule>(&shape)) {
    RequireDimension(cap->radius_m, "capsule radius", who);
    c.kind = CoreKind::kSegment;
    c.p0 = cap->a;
    c.p1 = cap->b;
    c.sweep_m = cap->radius_m;
    c.finite = Sane(cap->a) && Sane(cap->b);
    c.center = 0.5 * (cap->a + cap->b);
    c.bound_m = 0.5 * (cap->b - cap->a).norm() + cap->radius_m;
  } else if (const auto *box = std::get_if<Box>(&shape)) {
    for (int k = 0; k < 3; ++k) RequireDimension(box->half_extent_m[k], "box half extent", who);
    c.kind = CoreKind::kBox;
    c.R = box->R;
    c.half = box->half_extent_m;
    c.finite = Sane(box->center_m) && box->R.allFinite();
    if (c.finite && !(box->R.transpose() * box->R - Mat3::Identity()).isZero(1e-6)) {
      throw std::invalid_argument("contact: body '" + who + "': box R is not a rotation");
    }
    c.center = box->center_m;
    c.bound_m = box->half_extent_m.norm();
  } else {
    const auto &cyl = std::get<Cylinder>(shape);
    RequireDimension(cyl.height_m, "cylinder height", who);
    RequireDimension(cyl.radius_m, "cylinder radius", who);
    c.kind = CoreKind::kCylinder;
    c.finite = Sane(cyl.base_center_m) && cyl.axis.allFinite();
    if (c.finite && std::abs(cyl.axis.norm() - 1.0) > 1e-6) {
      throw std::invalid_argument("contact: body '" + who + "': cylinder axis is not a unit vector");
    }
    c.axis = cyl.axis;
    c.disk_radius_m = cyl.radius_m;
    c.p0 = cyl.base_center_m;
    c.p1 = cyl.base_center_m + cyl.height_m * cyl.axis;
    c.center = 0.5 * (c.p0 + c.p1);
    c.bound_m = std::hypot(0.5 * cyl.height_m, cyl.radius_m);
  }
  // Axis-aligned bounds: a segment's ends ± r; a box's center ± |R|·h; a cylinder's end
  // disks, whose extent along inertial axis k is r·√(1 − u_k²).
  switch (c.kind) {
    case CoreKind::kSegment:
      c.box_lo = c.p0.cwiseMin(c.p1).array() - c.sweep_m;
      c.box_hi = c.p0.cwiseMax(c.p1).array() + c.sweep_m;
      break;
    case CoreKind::kBox: {
      const Vec3 reach = c.R.cwiseAbs() * c.half;
      c.box_lo = c.center - reach;
      c.box_hi = c.center + reach;
      break;
    }
    case CoreKind::kCylinder: {
      const Vec3 reach =
          c.disk_radius_m * (Vec3::Ones() - c.axis.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
      c.box_lo = c.p0.cwiseMin(c.p1) - reach;
      c.box_hi = c.p0.cwiseMax(c.p1) + reach;
      break;
    }
  }
  return c;
}

/// Support point of the core in direction d (any length): argmax over the core of x·d.
/// Ties pick either vertex. No throwing operation (libccd calls it through a C pointer).
Vec3 CoreSupport(const Convex &s, const Vec3 &d) noexcept {
  switch (s.kind) {
    case CoreKind::kSegment:
      return d.dot(s.p1 - s.p0) > 0.0 ? s.p1 : s.p0;
    case CoreKind::kBox: {
      const Vec3 local = s.R.transpose() * d;
      Vec3 p = s.center;
      for (int k = 0; k < 3; ++k) p += s.R.col(k) * (local[k] >= 0.0 ? s.half[k] : -s.half[k]);
      return p;
    }
    case CoreKind::kCylinder: {
      const double along = d.dot(s.axis);
      Vec3 p = along > 0.0 ? s.p1 : s.p0;
      // The radial part of d as u × (d × u), not d − (d·u)·u: for d almost along the axis
      // the subtraction leaves rounding noise with a component along u, which normalised
      // would move the support point off the cap; the cross products stay orthogonal to u.
      const Vec3 radial = s.axis.cross(d.cross(s.axis));
      const double n = radial.norm();
      if (n > 0.0) p += (s.disk_radius_m / n) * radial;
      return p;
    }
  }
  return s.center;
}

/// Support point of the full shape (core swept by sweep_m).
Vec3 FullSupport(const Convex &s, const Vec3 &d, double extra_sweep_m) noexcept {
  Vec3 p = CoreSupport(s, d);
  const double n = d.norm();
  const double r = s.sweep_m + extra_sweep_m;
  if (n > 0.0 && r > 0.0) p += (r / n) * d;
  return p;
}

// ---------------------------------------------------------------------------------------
// GJK distance between two cores.

struct SimplexVertex {
  Vec3 w{Vec3::Zero()};   ///< point of the Minkowski difference A − B
  Vec3 pa{Vec3::Zero()};  ///< its point on A
  Vec3 pb{Vec3::Zero()};  ///< its point on B
};

struct Simplex {
  std::array<SimplexVertex, 4> v{};
  std::array<double, 4> lambda{};  ///< barycentric weights of the closest point
  int n{0};
};

/// Replaces the simplex by the smallest face whose relative interior holds the point of its
/// hull nearest the origin, sets the barycentric weights, returns that point. Enumerates the
/// (at most 15) faces: the nearest point lies in the relative interior of one face, where it
/// is the origin's projection onto the face's affine hull; any other face whose projection
/// falls inside it yields a point of the hull, hence no nearer. Degenerate faces are skipped
/// (their hull is covered by their own faces).
Vec3 ReduceSimplex(Simplex &s) {
  double best = std::numeric_limits<double>::infinity();
  unsigned best_mask = 1u;
  std::array<double, 4> best_lambda{1.0, 0.0, 0.0, 0.0};
  Vec3 best_v = s.v[0].w;
  const unsigned full = (1u << s.n) - 1u;
  for (unsigned mask = 1u; mask <= full; ++mask) {
    std::array<int, 4> idx{};
    int k = 0;
    for (int i = 0; i < s.n; ++i) {
      if (mask & (1u << i)) idx[k++] = i;
    }
    std::array<double, 4> lam{};
    Vec3 v;
    const Vec3 &w0 = s.v[idx[0]].w;
    if (k == 1) {
      lam[0] = 1.0;
      v = w0;
    } else {
      // v = w0 + Σ μ_c·e_c with e_c = w_c − w0 and μ from the normal equations
      // (EᵀE)·μ = −Eᵀ·w0, solved in closed form per size (fixed-size, no allocation).
      // A face is degenerate when det(EᵀE) is below kDegenerateGram·Π|e_c|².
      std::array<double, 3> mu{};
      if (k == 2) {
        const Vec3 e1 = s.v[idx[1]].w - w0;
        const double g11 = e1.squaredNorm();
        if (!(g11 > 0.0)) continue;
        mu[0] = -e1.dot(w0) / g11;
      } else if (k == 3) {
        const Vec3 e1 = s.v[idx[1]].w - w0, e2 = s.v[idx[2]].w - w0;
        const double g11 = e1.squaredNorm(), g12 = e1.dot(e2), g22 = e2.squaredNorm();
        const double det = g11 * g22 - g12 * g12;
        if (!(det > kDegenerateGram * g11 * g22)) continue;
        const double r1 = -e1.dot(w0), r2 = -e2.dot(w0);
        mu[0] = (r1 * g22 - r2 * g12) / det;
        mu[1] = (g11 * r2 - g12 * r1) / det;
      } else {
        // Four points span 3-D: the projection is the origin itself, E·μ = −w0.
        Mat3 E;
        E << s.v[idx[1]].w - w0, s.v[idx[2]].w - w0, s.v[idx[3]].w - w0;
        const double det = E.determinant();
        const double scale = E.col(0).norm() * E.col(1).norm() * E.col(2).norm();
        if (!(std::abs(det) > std::sqrt(kDegenerateGram) * scale)) continue;
        const Vec3 m = E.inverse() * (-w0);
        mu = {m[0], m[1], m[2]};
      }
      double sum = 0.0;
      bool inside = true;
      v = w0;
      for (int c = 0; c < k - 1; ++c) {
        lam[c + 1] = mu[c];
        sum += mu[c];
        inside = inside && mu[c] > 0.0;
        v += mu[c] * (s.v[idx[c + 1]].w - w0);
      }
      lam[0] = 1.0 - sum;
      if (!inside || !(lam[0] > 0.0)) continue;
      if (k == 4) v.setZero();
    }
    const double d2 = v.squaredNorm();
    if (d2 < best) {
      best = d2;
      best_mask = mask;
      best_v = v;
      best_lambda = lam;
    }
  }
  Simplex out;
  for (int i = 0, k = 0; i < s.n; ++i) {
    if (best_mask & (1u << i)) {
      out.v[out.n] = s.v[i];
      out.lambda[out.n] = best_lambda[k++];
      ++out.n;
    }
  }
  s = out;
  return best_v;
}

struct GjkResult {
  double distance_m{0.0};   ///< |v| when converged, else the lower bound
  Vec3 pa{Vec3::Zero()}, pb{Vec3::Zero()};
  int iterations{0};
  bool converged{false};
  bool intersecting{false};  ///< the cores intersect or touch within kCoreContactTol_m
};

/// Distance between the cores of a and b (radii ignored), GJK with a bounded loop.
GjkResult GjkCoreDistance(const Convex &a, const Convex &b) {
  GjkResult r;
  Simplex s;
  Vec3 v = a.center - b.center;  // a point of A − B
  r.pa = a.center;
  r.pb = b.center;
  double lower = 0.0;
  double last_norm = std::numeric_limits<double>::infinity();
  for (int it = 0; it < kGjkMaxIterations; ++it) {
    const double vn = v.norm();
    if (!(vn > kCoreContactTol_m)) {  // also catches NaN
      r.intersecting = std::isfinite(vn);
      r.converged = r.intersecting;
      r.distance_m = vn;
      r.iterations = it;
      return r;
    }
    SimplexVertex w;
    w.pa = CoreSupport(a, -v);
    w.pb = CoreSupport(b, v);
    w.w = w.pa - w.pb;
    r.iterations = it + 1;
    lower = std::max(lower, v.dot(w.w) / vn);
    // Gilbert's test: |v| is within tolerance of the lower bound v·w/|v|.
    if (vn - lower <= std::max(kGjkAbsTol_m, kGjkRelTol * vn)) {
      r.converged = true;
      r.distance_m = vn;
      return r;
    }
    s.v[s.n++] = w;
    v = ReduceSimplex(s);
    r.pa.setZero();
    r.pb.setZero();
    for (int i = 0; i < s.n; ++i) {
      r.pa += s.lambda[i] * s.v[i].pa;
      r.pb += s.lambda[i] * s.v[i].pb;
    }
    if (s.n == 4) {  // the origin is inside a tetrahedron of A − B
      r.intersecting = true;
      r.converged = true;
      r.distance_m = 0.0;
      return r;
    }
    // No progress: rounding limits the answer, which is then as good as it gets.
    const double new_norm = v.norm();
    if (!(new_norm < last_norm)) {
      r.converged = true;
      r.distance_m = new_norm;
      return r;
    }
    last_norm = new_norm;
  }
  r.converged = false;
  r.distance_m = std::max(lower, 0.0);
  return r;
}

// ---------------------------------------------------------------------------------------
// libccd glue. Callbacks are noexcept C-linkage functions reading a LibccdObject.

struct LibccdBudget {
  long calls{0};
};

// libccd 2.1's EPA can stop on a degenerate terminal GJK simplex and report a "touching
// contact" of depth ~0 for shapes that overlap deeply (danfis/libccd#25: two stacked cubes
// with the default first direction (1,0,0)). Measured here on overlapping pairs: axis-aligned
// cubes on a 0.25 m grid failed 17/1378 with (1,0,0), 100/1378 with the center difference,
// 11/1378 with either direction below; random boxes 12/2519 with (1,0,0), 0 with these;
// random capsules 14/490 with the center difference, 0 with these. The maximum of the two
// runs below failed in none of those trials (a correct EPA run is an inner estimate, a failed
// one ~0, so the larger is the better).
const std::array<Vec3, 2> kEpaFirstDirs{Vec3(0.5377, 0.8313, -0.1419),
                                        Vec3(-0.3, 0.4, 0.866)};

struct LibccdObject {
  const Convex *shape{nullptr};
  double extra_sweep_m{0.0};  ///< added sphere radius (bisection oracle)
  LibccdBudget *budget{nullptr};
  Vec3 first_dir{kEpaFirstDirs[0]};  ///< read from the first object only
};

Vec3 ToVec(const ccd_vec3_t *v) { return Vec3(v->v[0], v->v[1], v->v[2]); }
void FromVec(const Vec3 &x, ccd_vec3_t *out) {
  out->v[0] = x[0];
  out->v[1] = x[1];
  out->v[2] = x[2];
}

extern "C" {
static void UvmsCcdSupport(const void *obj, const ccd_vec3_t *dir, ccd_vec3_t *out) noexcept {
  const auto *o = static_cast<const LibccdObject *>(obj);
  if (++o->budget->calls > kLibccdSupportBudget) {
    FromVec(Vec3::Zero(), out);  // ends libccd's loops: see kLibccdSupportBudget
    return;
  }
  FromVec(FullSupport(*o->shape, ToVec(dir), o->extra_sweep_m), out);
}

static void UvmsCcdCenter(const void *obj, ccd_vec3_t *out) noexcept {
  FromVec(static_cast<const LibccdObject *>(obj)->shape->center, out);
}

static void UvmsCcdFirstDir(const void *o1, const void *, ccd_vec3_t *dir) noexcept {
  FromVec(static_cast<const LibccdObject *>(o1)->first_dir, dir);
}
}  // extern "C"

ccd_t MakeCcd() {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.first_dir = UvmsCcdFirstDir;
  ccd.support1 = UvmsCcdSupport;
  ccd.support2 = UvmsCcdSupport;
  ccd.center1 = UvmsCcdCenter;
  ccd.center2 = UvmsCcdCenter;
  ccd.max_iterations = static_cast<unsigned long>(kGjkMaxIterations);
  ccd.epa_tolerance = kEpaTolerance_m2;
  ccd.mpr_tolerance = kMprTolerance_m;
  ccd.dist_tolerance = kGjkAbsTol_m;  // unused by 2.1's public functions
  return ccd;
}

bool CcdIntersect(const Convex &a, const Convex &b, double extra_sweep_b_m) {
  LibccdBudget budget;
  const LibccdObject oa{&a, 0.0, &budget, kEpaFirstDirs[0]};
  const LibccdObject ob{&b, extra_sweep_b_m, &budget, kEpaFirstDirs[0]};
  const ccd_t ccd = MakeCcd();
  return ccdGJKIntersect(&oa, &ob, &ccd) != 0;
}

/// libccd return codes: 0 intersect (depth set), -1 no intersection, -2 allocation failure.
int CcdPenetration(const Convex &a, const Convex &b, bool use_mpr, double *depth,
                   const Vec3 &first_dir = kEpaFirstDirs[0]) {
  LibccdBudget budget;
  const LibccdObject oa{&a, 0.0, &budget, first_dir};
  const LibccdObject ob{&b, 0.0, &budget, first_dir};
  const ccd_t ccd = MakeCcd();
  ccd_real_t d = 0.0;
  ccd_vec3_t dir, pos;
  const int ret = use_mpr ? ccdMPRPenetration(&oa, &ob, &ccd, &d, &dir, &pos)
                          : ccdGJKPenetration(&oa, &ob, &ccd, &d, &dir, &pos);
  *depth = d;
  return ret;
}

DistanceResult NanResult() {
  DistanceResult r;
  r.distance_m = std::numeric_limits<double>::quiet_NaN();
  r.converged = false;
  return r;
}

/// The general path: GJK on the cores, libccd penetration when they intersect.
DistanceResult GeneralDistance(const Convex &a, const Convex &b) {
  if (!a.finite || !b.finite) return NanResult();
  const GjkResult g = GjkCoreDistance(a, b);
  DistanceResult r;
  r.gjk_iterations = g.iterations;
  r.converged = g.converged;
  if (!std::isfinite(g.distance_m)) return NanResult();
  if (!g.intersecting) {
    r.method = DistanceMethod::kGjk;
    r.distance_m = g.distance_m - a.sweep_m - b.sweep_m;
    const Vec3 ab = g.pb - g.pa;
    const double n = ab.norm();
    const Vec3 u = n > 0.0 ? Vec3(ab / n) : Vec3::Zero();
    r.point_a_m = g.pa + a.sweep_m * u;
    r.point_b_m = g.pb - b.sweep_m * u;
    return r;
  }
  r.point_a_m = g.pa;
  r.point_b_m = g.pb;
  // EPA gives the minimal translation that separates the shapes (from an inner polytope, so
  // at most the true depth): the larger of two runs from different first directions (see
  // kEpaFirstDirs). When both fail (allocation) or claim a touching contact, MPR: the depth
  // along its final portal normal, a supporting plane, hence at least the true depth: the
  // conservative side for a monitor.
  double depth = 0.0;
  int ret = -1;
  for (const Vec3 &dir : kEpaFirstDirs) {
    double run_depth = 0.0;
    if (CcdPenetration(a, b, false, &run_depth, dir) == 0 && std::isfinite(run_depth)) {
      depth = ret == 0 ? std::max(depth, run_depth) : run_depth;
      ret = 0;
    }
  }
  r.method = DistanceMethod::kLibccdEpa;
  if (ret != 0 || !(depth > kCoreContactTol_m)) {
    double mpr_depth = 0.0;
    if (CcdPenetration(a, b, true, &mpr_depth) == 0 && mpr_depth > kCoreContactTol_m) {
      ret = 0;
      depth = mpr_depth;
      r.method = DistanceMethod::kLibccdMpr;
    }
  }
  if (ret == 0 && std::isfinite(depth)) {
    r.distance_m = -std::max(depth, 0.0);
  } else {
    // libccd sees no overlap of the full shapes although the cores meet within
    // kCoreContactTol_m: a touching contact (exact when both radii are zero).
    r.method = DistanceMethod::kTouching;
    r.distance_m = std::min(g.distance_m - a.sweep_m - b.sweep_m, 0.0);
  }
  return r;
}

/// The monitor's path: the closed form for two capsules whose segments do not meet.
DistanceResult PairDistance(const Convex &a, const Convex &b) {
  if (a.kind == CoreKind::kSegment && b.kind == CoreKind::kSegment && a.finite && b.finite) {
    DistanceResult r;
    const double d = SegmentSegmentDistance(a.p0, a.p1, b.p0, b.p1, &r.point_a_m, &r.point_b_m);
    if (d > kCoreContactTol_m) {
      r.method = DistanceMethod::kClosedForm;
      r.distance_m = d - a.sweep_m - b.sweep_m;
      const Vec3 u = (r.point_b_m - r.point_a_m) / d;
      r.point_a_m += a.sweep_m * u;
      r.point_b_m -= b.sweep_m * u;
      return r;
    }
  }
  return GeneralDistance(a, b);
}

/// A lower bound on the signed distance of two shapes from their bounding spheres and boxes.
/// Separated shapes are at least as far apart as their bounds. Overlapping ones: a
/// translation that separates the bounds separates the shapes, so the penetration depth is
/// at most R_a + R_b − |c_a − c_b| (spheres) and the smallest per-axis overlap (boxes), and
/// −depth is above both.
double LowerBound(const Convex &a, const Convex &b) {
  const double spheres = (a.center - b.center).norm() - a.bound_m - b.bound_m;
  const Vec3 gap = (a.box_lo - b.box_hi).cwiseMax(b.box_lo - a.box_hi);
  const double boxes = gap.maxCoeff() <= 0.0 ? gap.maxCoeff() : gap.cwiseMax(0.0).norm();
  return std::max(spheres, boxes);
}

/// Point–segment closest parameter in [0, 1].
double ClampedParam(const Vec3 &x, const Vec3 &p, const Vec3 &d) {
  const double dd = d.squaredNorm();
  if (!(dd > 0.0)) return 0.0;
  return std::clamp((x - p).dot(d) / dd, 0.0, 1.0);
}

/// Name pairs stored as (min, max); looked up with string_views without copying.
std::pair<std::string_view, std::string_view> Ordered(std::string_view x, std::string_view y) {
  return x < y ? std::make_pair(x, y) : std::make_pair(y, x);
}

}  // namespace

// ---------------------------------------------------------------------------------------

double SegmentSegmentDistance(const Vec3 &p1, const Vec3 &q1, const Vec3 &p2, const Vec3 &q2,
                              Vec3 *c1, Vec3 *c2) {
  // |P(s) − Q(t)|², P(s) = p1 + s·d1, Q(t) = p2 + t·d2, is a convex quadratic on [0,1]²:
  // its minimum is the interior stationary point when that lies inside, else on an edge of
  // the square, i.e. an endpoint of one segment against the other segment (4 candidates).
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  double best_s = 0.0, best_t = ClampedParam(p1, p2, d2);
  double best = (p1 - (p2 + best_t * d2)).squaredNorm();
  auto consider = [&](double s, double t) {
    const double dist2 = ((p1 + s * d1) - (p2 + t * d2)).squaredNorm();
    if (dist2 < best) {
      best = dist2;
      best_s = s;
      best_t = t;
    }
  };
  consider(1.0, ClampedParam(q1, p2, d2));
  consider(ClampedParam(p2, p1, d1), 0.0);
  consider(ClampedParam(q2, p1, d1), 1.0);
  // Interior: ∂/∂s = ∂/∂t = 0 → [a −b; b −e]·(s, t) = (−c, −f), a = d1·d1, b = d1·d2,
  // e = d2·d2, c = d1·r, f = d2·r; determinant a·e − b² = a·e·sin²(angle). Near-parallel
  // segments (sin² below 1e-13, rounding-dominated) use the endpoint candidates only: their
  // error is then below angle·length.
  const double a = d1.squaredNorm(), b = d1.dot(d2), e = d2.squaredNorm();
  const double denom = a * e - b * b;
  if (denom > 1e-13 * a * e && a > 0.0 && e > 0.0) {
    const double c = d1.dot(r), f = d2.dot(r);
    const double s = (b * f - c * e) / denom;
    const double t = (a * f - b * c) / denom;
    if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0) consider(s, t);
  }
  if (c1) *c1 = p1 + best_s * d1;
  if (c2) *c2 = p2 + best_t * d2;
  return std::sqrt(best);
}

double CapsuleCapsuleDistance(const Capsule &a, const Capsule &b) {
  return SegmentSegmentDistance(a.a, a.b, b.a, b.b) - a.radius_m - b.radius_m;
}

DistanceResult ShapeDistance(const Shape &a, const Shape &b) {
  return GeneralDistance(MakeConvex(a, "a"), MakeConvex(b, "b"));
}

bool LibccdIntersect(const Shape &a, const Shape &b) {
  const Convex ca = MakeConvex(a, "a"), cb = MakeConvex(b, "b");
  if (!ca.finite || !cb.finite) return false;
  return CcdIntersect(ca, cb, 0.0);
}

std::optional<double> LibccdPenetrationDepth(const Shape &a, const Shape &b, bool use_mpr) {
  const Convex ca = MakeConvex(a, "a"), cb = MakeConvex(b, "b");
  if (!ca.finite || !cb.finite) return std::nullopt;
  double depth = 0.0;
  if (CcdPenetration(ca, cb, use_mpr, &depth) != 0) return std::nullopt;
  return depth;
}

double LibccdBisectionDistance(const Shape &a, const Shape &b, double tol_m) {
  const Convex ca = MakeConvex(a, "a"), cb = MakeConvex(b, "b");
  if (!ca.finite || !cb.finite) return std::numeric_limits<double>::quiet_NaN();
  if (CcdIntersect(ca, cb, 0.0)) return 0.0;
  // The centers are points of the shapes: sweeping b by their distance surely intersects a.
  double lo = 0.0, hi = (ca.center - cb.center).norm() + 1e-6;
  for (int it = 0; it < 200 && hi - lo > tol_m; ++it) {
    const double mid = 0.5 * (lo + hi);
    (CcdIntersect(ca, cb, mid) ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// ---------------------------------------------------------------------------------------

ContactMonitor::ContactMonitor(double clearance_m,
                               std::vector<std::pair<std::string, std::string>> ignore_pairs)
    : clearance_m_(clearance_m) {
  if (!std::isfinite(clearance_m) || clearance_m < 0.0) {
    throw std::invalid_argument("ContactMonitor: clearance_m must be finite and >= 0");
  }
  for (auto &p : ignore_pairs) {
    if (p.second < p.first) std::swap(p.first, p.second);
    ignore_.insert(std::move(p));
  }
}

bool ContactMonitor::IsChecked(const Body &a, const Body &b) const {
  if (a.group >= 0 && a.group == b.group) return false;
  if (ignore_.empty()) return true;
  const auto key = Ordered(a.name, b.name);
  // std::set<pair<string, string>> has no heterogeneous lookup: binary search by hand.
  const auto it = std::lower_bound(
      ignore_.begin(), ignore_.end(), key,
      [](const std::pair<std::string, std::string> &x,
         const std::pair<std::string_view, std::string_view> &y) {
        return std::string_view(x.first) < y.first ||
               (std::string_view(x.first) == y.first && std::string_view(x.second) < y.second);
      });
  return !(it != ignore_.end() && std::string_view(it->first) == key.first &&
           std::string_view(it->second) == key.second);
}

std::vector<ContactPair> ContactMonitor::CheckedPairs(const std::vector<Body> &bodies) const {
  std::vector<ContactPair> out;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < bodies.size(); ++j) {
      if (IsChecked(bodies[i], bodies[j])) out.push_back(ContactPair{i, j});
    }
  }
  return out;
}

ContactMonitor::Report ContactMonitor::Check(const std::vector<Body> &bodies) const {
  return Check(bodies, CheckedPairs(bodies));
}

ContactMonitor::Report ContactMonitor::Check(const std::vector<Body> &bodies,
                                             const std::vector<ContactPair> &pairs) const {
  Report rep;
  rep.min_distance_m = std::numeric_limits<double>::infinity();
  std::vector<Convex> shapes;
  shapes.reserve(bodies.size());
  for (const Body &body : bodies) shapes.push_back(MakeConvex(body.shape, body.name));

  auto set_pair = [&](std::size_t i, std::size_t j) {
    rep.pair = ContactPair{i, j};
    rep.body_a = bodies[i].name;
    rep.body_b = bodies[j].name;
  };

  // Candidates with a lower bound on their signed distance (LowerBound: bounding spheres
  // and axis-aligned boxes), visited from the smallest bound.
  struct Candidate {
    double lower_bound_m;
    std::size_t i, j;
  };
  std::vector<Candidate> candidates;
  candidates.reserve(pairs.size());
  for (const ContactPair &p : pairs) {  // lexicographic: the first non-finite pair is named
    const std::size_t i = p.i, j = p.j;
    if (i >= j || j >= bodies.size())
      throw std::invalid_argument("ContactMonitor::Check: a pair outside the body list");
    if (!shapes[i].finite || !shapes[j].finite) {
      set_pair(i, j);
      rep.min_distance_m = std::numeric_limits<double>::quiet_NaN();
      rep.breach = true;
      return rep;
    }
    candidates.push_back(Candidate{LowerBound(shapes[i], shapes[j]), i, j});
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate &x, const Candidate &y) {
                     return x.lower_bound_m < y.lower_bound_m;
                   });
  for (const Candidate &c : candidates) {
    if (c.lower_bound_m >= rep.min_distance_m) break;  // sorted: no later pair can be closer
    const DistanceResult d = PairDistance(shapes[c.i], shapes[c.j]);
    if (std::isnan(d.distance_m)) {
      set_pair(c.i, c.j);
      rep.min_distance_m = d.distance_m;
      rep.method = d.method;
      rep.breach = true;
      return rep;
    }
    if (d.distance_m < rep.min_distance_m) {
      rep.min_distance_m = d.distance_m;
      rep.method = d.method;
      rep.pair = ContactPair{c.i, c.j};
    }
  }
  if (!candidates.empty() && rep.min_distance_m < std::numeric_limits<double>::infinity())
    set_pair(rep.pair.i, rep.pair.j);
  // A breach: closer than the clearance, or touching/penetrating even with clearance 0
  // (SPEC §5: a contact ends the run). Written so that NaN is a breach.
  rep.breach = !(rep.min_distance_m >= clearance_m_) || rep.min_distance_m <= 0.0;
  return rep;
}

}  // namespace uvms::plant
