// Accuracy of fcl_disk::diskShapeDistance() for a disk against every FCL
// primitive, against the independent long-double reference of
// reference_disk_shape.h, on the configuration families of
// disk_shape_families.h (double and float); and of the reference itself against
// hand-derived closed forms and the distances fixed by construction.
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/disk.h>
#include <fcl_disk/disk_shape_distance.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "disk_shape_families.h"
#include "reference_disk_shape.h"

namespace {

namespace ref = fcl_disk_test::ref;
namespace fam = fcl_disk_test::shape_families;
using fam::DiskShapeCase;
using fam::Family;
using ref::M3;
using ref::Real;
using ref::V3;

// ---- tolerances -------------------------------------------------------------

/// The guarantee of disk_shape_distance.h in double: |distance - d_true|, the
/// points' distances from their shapes and | |p - q| - distance | are at most
/// 1e-12 * scale.
constexpr double kDoubleRelative = 1e-12;

/// Float: the solver promotes to double and rounds to float, so "a few float
/// ulps" of the scale: 1/2 ulp per rounded coordinate and per rounded distance,
/// plus a float rotation being orthonormal only to ~1 ulp (the reference
/// projects it onto the rotations, the solver uses it as given, so "the" shape
/// is defined to ~1 ulp of its size). 8 ulps of the scale.
constexpr double kFloatUlpsOfScale = 8;

/// Points are stored in world coordinates, each coordinate rounded by half an
/// ulp of its magnitude (up to |c| + scale); forming them as c + R x adds about
/// as much again. No solver can beat this far from the origin (far family:
/// 4 eps 1e6 = 9e-10 in double, above 1e-12 * scale), so point checks allow this
/// many eps of the world magnitude on top of the relative tolerance. It is
/// negligible for scenes near the origin.
constexpr double kWorldRoundingEps = 4;

/// The reference against hand-derived closed forms (inputs exact in long
/// double): ~100 long-double ulps, five orders below the solver's tolerance.
constexpr double kReferenceClosedFormRelative = 1e-17;

/// The reference against the distance fixed by construction: the construction
/// holds in exact arithmetic before the poses are rounded to double, and the
/// distance is 1-Lipschitz in the poses' translations and moves by at most
/// |x| * (rotation error) for shape points x, so the rounding moves it by a few
/// eps of the largest coordinate involved (world translations, the shape's
/// extent about its origin, the scale): 8 eps of that. Measured: <= 2 eps.
constexpr double kConstructionRoundingEps = 8;

/// Largest certificate gap (distance - lower_bound) of the reference, relative
/// to its scale. The certificate's direction comes from the nearest pair, which
/// the golden-section search locates to ~sqrt(eps_ld) along a smooth minimum;
/// measured <= 1e-12 only where a curved contact (cone, ellipsoid) ends up
/// ~1e-10 * scale apart after rounding a far-from-origin pose, <= 5e-15
/// everywhere else. The check catches a broken support function or a search
/// that missed the minimum by more than that.
constexpr double kReferenceCertificateRelative = 1e-11;

/// diskShapeIntersect(): pairs the reference finds farther apart than this
/// (relative) must not intersect: 100x the header's 1e-13 decision tolerance.
constexpr double kClearlyApartRelative = 1e-11;

/// Cases per family and shape. The reference costs 0.5-4 ms per case (long
/// double, ~8.5e3 point-to-shape distances), so these keep the whole file to
/// ~15 s on two cores while covering every sub-kind of every family many times.
constexpr int kDoubleCasesPerFamily = 200;
constexpr int kFloatCasesPerFamily = 100;
constexpr std::uint64_t kSeed = 20250101;

/// At most this many failing cases are printed per check (the count always is).
constexpr int kMaxReportedFailures = 6;

// ---- FCL shapes from the reference's structs ----------------------------------

template <typename S>
fcl::Vector3<S> toFcl3(const V3& x) {
  return fcl::Vector3<S>(S(x.x()), S(x.y()), S(x.z()));
}

template <typename S>
fcl::Transform3<S> toPose(const M3& R, const V3& t) {
  fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  X.linear() = R.cast<S>();
  X.translation() = t.cast<S>();
  return X;
}

template <typename S> fcl::Sphere<S> toFcl(const ref::Sphere& s) { return fcl::Sphere<S>(S(s.radius)); }
template <typename S> fcl::Box<S> toFcl(const ref::Box& s) {
  return fcl::Box<S>(S(s.side.x()), S(s.side.y()), S(s.side.z()));
}
template <typename S> fcl::Capsule<S> toFcl(const ref::Capsule& s) { return fcl::Capsule<S>(S(s.radius), S(s.lz)); }
template <typename S> fcl::Cylinder<S> toFcl(const ref::Cylinder& s) { return fcl::Cylinder<S>(S(s.radius), S(s.lz)); }
template <typename S> fcl::Cone<S> toFcl(const ref::Cone& s) { return fcl::Cone<S>(S(s.radius), S(s.lz)); }
template <typename S> fcl::Ellipsoid<S> toFcl(const ref::Ellipsoid& s) {
  return fcl::Ellipsoid<S>(S(s.radii.x()), S(s.radii.y()), S(s.radii.z()));
}
template <typename S> fcl::Convex<S> toFcl(const ref::Convex& s) {
  auto vertices = std::make_shared<std::vector<fcl::Vector3<S>>>();
  for (const V3& x : s.vertices) vertices->push_back(toFcl3<S>(x));
  auto faces = std::make_shared<std::vector<int>>();
  for (const auto& f : s.faces) {
    faces->push_back(int(f.size()));
    faces->insert(faces->end(), f.begin(), f.end());
  }
  return fcl::Convex<S>(vertices, int(s.faces.size()), faces);
}
template <typename S> fcl::Halfspace<S> toFcl(const ref::Halfspace& s) {
  return fcl::Halfspace<S>(toFcl3<S>(s.n), S(s.d));
}
template <typename S> fcl::Plane<S> toFcl(const ref::Plane& s) { return fcl::Plane<S>(toFcl3<S>(s.n), S(s.d)); }
template <typename S> fcl::TriangleP<S> toFcl(const ref::TriangleP& s) {
  return fcl::TriangleP<S>(toFcl3<S>(s.a), toFcl3<S>(s.b), toFcl3<S>(s.c));
}

// ---- printing -----------------------------------------------------------------

std::string str(Real x) {
  std::ostringstream out;
  out << std::setprecision(17) << double(x);
  return out.str();
}
std::string str(const V3& x) { return "[" + str(x.x()) + ", " + str(x.y()) + ", " + str(x.z()) + "]"; }
std::string str(const M3& R) {
  return "[" + str(V3(R.row(0).transpose())) + ", " + str(V3(R.row(1).transpose())) + ", " +
         str(V3(R.row(2).transpose())) + "]";
}

std::string dims(const ref::Sphere& s) { return "Sphere(radius " + str(s.radius) + ")"; }
std::string dims(const ref::Box& s) { return "Box(sides " + str(s.side) + ")"; }
std::string dims(const ref::Capsule& s) { return "Capsule(radius " + str(s.radius) + ", lz " + str(s.lz) + ")"; }
std::string dims(const ref::Cylinder& s) { return "Cylinder(radius " + str(s.radius) + ", lz " + str(s.lz) + ")"; }
std::string dims(const ref::Cone& s) { return "Cone(radius " + str(s.radius) + ", lz " + str(s.lz) + ")"; }
std::string dims(const ref::Ellipsoid& s) { return "Ellipsoid(radii " + str(s.radii) + ")"; }
std::string dims(const ref::Convex& s) {
  std::string out = "Convex(vertices";
  for (const V3& x : s.vertices) out += " " + str(x);
  out += "; faces";
  for (const auto& f : s.faces) {
    out += " {";
    for (size_t i = 0; i < f.size(); ++i) out += (i ? "," : "") + std::to_string(f[i]);
    out += "}";
  }
  return out + ")";
}
std::string dims(const ref::Halfspace& s) { return "Halfspace(n " + str(s.n) + ", d " + str(s.d) + ")"; }
std::string dims(const ref::Plane& s) { return "Plane(n " + str(s.n) + ", d " + str(s.d) + ")"; }
std::string dims(const ref::TriangleP& s) {
  return "TriangleP(" + str(s.a) + ", " + str(s.b) + ", " + str(s.c) + ")";
}

/// The whole case at full precision: enough to rebuild it.
template <typename Shape>
std::string describe(const DiskShapeCase<Shape>& c) {
  return c.family + " (" + c.detail + "): disk radius " + str(c.radius) + " R_D " + str(c.R_D) +
         " t_D " + str(c.t_D) + "; " + dims(c.shape) + " R_S " + str(c.shape.R) + " t_S " +
         str(c.shape.t);
}

/// Collects the failures of one check; prints the first few in full.
class FailureLog {
 public:
  explicit FailureLog(std::string check) : check_(std::move(check)) {}
  void add(const std::string& message) {
    if (count_ < kMaxReportedFailures) ADD_FAILURE() << check_ << ": " << message;
    ++count_;
  }
  ~FailureLog() { EXPECT_EQ(count_, 0) << check_ << ": " << count_ << " failing cases in total"; }

 private:
  std::string check_;
  int count_ = 0;
};

// ---- the reference on a family, in two threads ----------------------------------

template <typename Shape>
struct Referenced {
  DiskShapeCase<Shape> c;
  ref::Disk disk;
  ref::Result reference;
};

template <typename Shape>
std::vector<Referenced<Shape>> referenced(const std::vector<DiskShapeCase<Shape>>& cases) {
  std::vector<Referenced<Shape>> out(cases.size());
  const auto work = [&](size_t begin, size_t step) {
    for (size_t i = begin; i < cases.size(); i += step) {
      out[i].c = cases[i];
      out[i].disk = cases[i].disk();
      out[i].reference = ref::referenceDistance(out[i].disk, cases[i].shape);
    }
  };
  std::thread other(work, 1, 2);
  work(0, 2);
  other.join();
  return out;
}

/// fcl::distance between the disk and a mesh made of `triangle` alone (an
/// OBBRSS model, at pose X_WS).
template <typename S>
fcl::DistanceResult<S> oneTriangleMeshDistance(Real radius, const fcl::Transform3<S>& X_WD,
                                               const fcl::TriangleP<S>& triangle,
                                               const fcl::Transform3<S>& X_WS) {
  auto mesh = std::make_shared<fcl::BVHModel<fcl::OBBRSS<S>>>();
  mesh->beginModel();
  mesh->addTriangle(triangle.a, triangle.b, triangle.c);
  mesh->endModel();
  const fcl::CollisionObject<S> disk(std::make_shared<fcl_disk::Disk<S>>(S(radius)), X_WD);
  const fcl::CollisionObject<S> leaf(mesh, X_WS);
  fcl::DistanceRequest<S> request;
  request.enable_nearest_points = true;
  fcl::DistanceResult<S> result;
  fcl::distance(&disk, &leaf, request, result);
  return result;
}

// ---- checks -------------------------------------------------------------------

/// The reference against the construction and its own certificate (double cases).
template <typename Shape>
void checkReference(const std::vector<Referenced<Shape>>& cases) {
  FailureLog construction("reference vs constructed distance");
  FailureLog certificate("reference certificate gap");
  const double eps = std::numeric_limits<double>::epsilon();
  for (const auto& rc : cases) {
    const ref::Result& r = rc.reference;
    if (rc.c.hasKnownDistance()) {
      const Real magnitude = r.scale + rc.c.t_D.norm() + rc.c.shape.t.norm() +
                             ref::boundingRadius(rc.c.shape) + (rc.c.shape.t - rc.c.t_D).norm();
      const Real tol = kConstructionRoundingEps * eps * magnitude;
      const Real err = std::fabs(r.distance - rc.c.known_distance);
      if (!(err <= tol))
        construction.add("reference " + str(r.distance) + " constructed " + str(rc.c.known_distance) +
                         " (error " + str(err) + ", tolerance " + str(tol) + ", method " + r.method +
                         ") " + describe(rc.c));
    }
    if (!(r.certifiedGap() <= kReferenceCertificateRelative * r.scale))
      certificate.add("gap " + str(r.certifiedGap()) + " = " + str(r.certifiedGap() / r.scale) +
                      " * scale (distance " + str(r.distance) + ", method " + r.method + ") " +
                      describe(rc.c));
  }
}

/// The solver in S against the reference, on cases exactly representable in S.
template <typename S, typename Shape>
void checkSolver(const std::vector<Referenced<Shape>>& cases) {
  const bool is_float = std::is_same<S, float>::value;
  const double eps = std::numeric_limits<S>::epsilon();
  const double relative = is_float ? kFloatUlpsOfScale * eps : kDoubleRelative;
  const std::string type = is_float ? "float" : "double";
  FailureLog distance_log(type + " distance vs reference");
  FailureLog points_log(type + " nearest points on their shapes");
  FailureLog pair_log(type + " |p_W_shape - p_W_disk| == distance");
  FailureLog bound_log(type + " lower_bound <= reference distance");
  FailureLog intersect_log(type + " diskShapeIntersect vs reference");
  FailureLog mesh_log(type + " one-triangle mesh: fcl::distance vs reference");
  FailureLog mesh_points_log(type + " one-triangle mesh: nearest points on their shapes, |p - q| == distance");
  for (const auto& rc : cases) {
    const auto& c = rc.c;
    const ref::Result& r = rc.reference;
    const auto shape = toFcl<S>(c.shape);
    const fcl::Transform3<S> X_WD = toPose<S>(c.R_D, c.t_D), X_WS = toPose<S>(c.shape.R, c.shape.t);
    const auto got = fcl_disk::diskShapeDistance(S(c.radius), X_WD, shape, X_WS);
    const double scale = double(r.scale);
    const double tol = relative * scale;
    const double world = kWorldRoundingEps * eps * (double(std::max(c.t_D.norm(), c.shape.t.norm())) + scale);
    const double expected = double(r.distance);
    const double d = double(got.distance);
    const auto context = [&] {
      return " (scale " + str(scale) + ", reference " + str(r.distance) + " by " + r.method + ") " +
             describe(c);
    };
    if (!(std::fabs(d - expected) <= tol))
      distance_log.add("got " + str(d) + ", error " + str((d - expected) / scale) + " * scale" +
                       context());
    const V3 p = got.p_W_disk.template cast<Real>();
    const V3 q = got.p_W_shape.template cast<Real>();
    const double off_disk = double(ref::distanceToDisk(p, rc.disk));
    const double off_shape = double(ref::distanceToShape(q, c.shape));
    if (!(off_disk <= tol + world && off_shape <= tol + world))
      points_log.add("p_W_disk " + str(p) + " is " + str(off_disk) + " from the disk, p_W_shape " +
                     str(q) + " is " + str(off_shape) + " from the shape (tolerance " +
                     str(tol + world) + ")" + context());
    const double pair = double((q - p).norm());
    if (!(std::fabs(pair - d) <= tol + 2 * world))
      pair_log.add("|p - q| = " + str(pair) + ", distance " + str(d) + context());
    if (!(double(got.lower_bound) <= expected + tol))
      bound_log.add("lower_bound " + str(got.lower_bound) + " exceeds the distance by " +
                    str((double(got.lower_bound) - expected) / scale) + " * scale" + context());
    if constexpr (std::is_same<Shape, ref::TriangleP>::value) {
      // The same triangle as the one leaf of a mesh, through fcl::distance:
      // the traversal's closed forms and certificates (src/environment_bounds.h)
      // answer some configurations without the solver.
      const auto leaf = oneTriangleMeshDistance<S>(c.radius, X_WD, shape, X_WS);
      const double leaf_d = double(leaf.min_distance);
      if (!(std::fabs(leaf_d - expected) <= tol))
        mesh_log.add("got " + str(leaf_d) + ", error " + str((leaf_d - expected) / scale) +
                     " * scale" + context());
      const V3 leaf_q = leaf.nearest_points[0].template cast<Real>();  // the mesh is o1
      const V3 leaf_p = leaf.nearest_points[1].template cast<Real>();
      const double leaf_off_disk = double(ref::distanceToDisk(leaf_p, rc.disk));
      const double leaf_off_shape = double(ref::distanceToShape(leaf_q, c.shape));
      if (!(leaf_off_disk <= tol + world && leaf_off_shape <= tol + world &&
            std::fabs(double((leaf_q - leaf_p).norm()) - leaf_d) <= tol + 2 * world))
        mesh_points_log.add("disk point " + str(leaf_p) + " is " + str(leaf_off_disk) +
                            " from the disk, triangle point " + str(leaf_q) + " is " +
                            str(leaf_off_shape) + " from the triangle" + context());
    }
    const bool apart = expected > kClearlyApartRelative * scale;
    const bool deep_inside = c.family == fam::familyName(Family::inside);
    if (!is_float && (apart || deep_inside)) {
      const bool hit = fcl_disk::diskShapeIntersect(S(c.radius), X_WD, shape, X_WS);
      if (hit == apart)
        intersect_log.add(std::string("diskShapeIntersect says ") + (hit ? "true" : "false") +
                          context());
    }
  }
}

template <typename Shape>
void runFamily(Family family) {
  const auto cases = fam::makeFamily<Shape>(family, kDoubleCasesPerFamily, kSeed);
  if (cases.empty()) GTEST_SKIP() << "no such configuration for this shape";
  const auto double_cases = referenced(cases);
  checkReference(double_cases);
  checkSolver<double>(double_cases);
  std::vector<DiskShapeCase<Shape>> float_cases;
  for (int i = 0; i < kFloatCasesPerFamily && i < int(cases.size()); ++i)
    float_cases.push_back(fam::roundedTo<float>(cases[i]));
  checkSolver<float>(referenced(float_cases));
}

enum class Kind { sphere, box, capsule, cylinder, cone, ellipsoid, convex, halfspace, plane, triangle };

const char* kindName(Kind k) {
  switch (k) {
    case Kind::sphere: return "Sphere";
    case Kind::box: return "Box";
    case Kind::capsule: return "Capsule";
    case Kind::cylinder: return "Cylinder";
    case Kind::cone: return "Cone";
    case Kind::ellipsoid: return "Ellipsoid";
    case Kind::convex: return "Convex";
    case Kind::halfspace: return "Halfspace";
    case Kind::plane: return "Plane";
    case Kind::triangle: return "TriangleP";
  }
  return "?";
}

struct Param {
  Kind kind;
  Family family;
};

std::vector<Param> allParams() {
  std::vector<Param> out;
  for (Kind k : {Kind::sphere, Kind::box, Kind::capsule, Kind::cylinder, Kind::cone, Kind::ellipsoid,
                 Kind::convex, Kind::halfspace, Kind::plane, Kind::triangle})
    for (Family f : fam::allFamilies()) out.push_back({k, f});
  return out;
}

class DiskShapeAccuracy : public ::testing::TestWithParam<Param> {};

TEST_P(DiskShapeAccuracy, SolverMatchesReference) {
  const Family f = GetParam().family;
  switch (GetParam().kind) {
    case Kind::sphere: return runFamily<ref::Sphere>(f);
    case Kind::box: return runFamily<ref::Box>(f);
    case Kind::capsule: return runFamily<ref::Capsule>(f);
    case Kind::cylinder: return runFamily<ref::Cylinder>(f);
    case Kind::cone: return runFamily<ref::Cone>(f);
    case Kind::ellipsoid: return runFamily<ref::Ellipsoid>(f);
    case Kind::convex: return runFamily<ref::Convex>(f);
    case Kind::halfspace: return runFamily<ref::Halfspace>(f);
    case Kind::plane: return runFamily<ref::Plane>(f);
    case Kind::triangle: return runFamily<ref::TriangleP>(f);
  }
}

INSTANTIATE_TEST_SUITE_P(AllPairs, DiskShapeAccuracy, ::testing::ValuesIn(allParams()),
                         [](const ::testing::TestParamInfo<Param>& info) {
                           return std::string(kindName(info.param.kind)) + "_" +
                                  fam::familyName(info.param.family);
                         });

// ---- a mesh leaf whose face normal is rounding noise --------------------------

/// A triangle whose third vertex lies on the line of the other two (to the
/// rounding of its coordinates) as the one leaf of a mesh: its cross product
/// is rounding noise, so its "face normal" is not perpendicular to it, and a
/// face certificate built on that normal would claim a distance larger than
/// the true one (fuzz_disk_environment: regression-sliver-face-certificate).
/// The leaf's answer must be the reference's.
TEST(MeshLeaf, CollinearTriangleMatchesReference) {
  const auto rotation = [](std::initializer_list<double> column_major) {
    M3 R;
    int i = 0;
    for (const double x : column_major) R(i % 3, i / 3) = Real(x), ++i;
    return R;
  };
  const M3 R_D = rotation({0.11415046763783825, 0.44970740660628905, -0.88585152208567586,
                           0.47010051683131787, 0.76108218581127429, 0.44694452733606749,
                           0.87520007701838709, -0.46745818517187049, -0.12452979684730305});
  const V3 t_D(-1.0072556649118791, -1.098901350423438, -1.2650720988784618);
  const Real radius = 0.20011749446860455;
  ref::TriangleP triangle;
  triangle.R = rotation({-0.93726937521191711, -0.13489664495390449, 0.32144830606186553,
                         -0.27055498342829165, -0.29999435606256653, -0.91476958151915111,
                         0.21983202503725288, -0.94435495525294211, 0.24467856313382735});
  triangle.t = V3(-0.17649347676813915, -0.32726787212939651, -0.29499504081788358);
  triangle.a = V3(-0.38435950255588613, 0.26521705958648045, -0.59230945296406501);
  triangle.b = V3(0.78945601586938285, 0.57232013427939266, 0.31230640115968566);
  triangle.c = V3(0.26694825202560585, 0.43561744266511587, -0.090370850637034247);
  const ref::Result reference =
      ref::referenceDistance(ref::makeDisk(radius, R_D, t_D), triangle);
  const auto got = oneTriangleMeshDistance<double>(radius, toPose<double>(R_D, t_D),
                                                   toFcl<double>(triangle),
                                                   toPose<double>(triangle.R, triangle.t));
  EXPECT_LE(std::fabs(double(got.min_distance) - double(reference.distance)),
            kDoubleRelative * double(reference.scale))
      << "mesh leaf " << str(got.min_distance) << ", reference " << str(reference.distance);
}

// ---- the reference against hand-derived closed forms ---------------------------

M3 rotX(Real angle) {
  M3 R;
  R << 1, 0, 0, 0, std::cos(angle), -std::sin(angle), 0, std::sin(angle), std::cos(angle);
  return R;
}

template <typename Shape>
Shape posed(Shape s, const M3& R, const V3& t) {
  s.R = R;
  s.t = t;
  return s;
}

/// Checks the reference on one pair against a closed-form distance, its points
/// and its certificate.
template <typename Shape>
void expectReference(const ref::Disk& disk, const Shape& shape, Real expected, const char* what) {
  const ref::Result r = ref::referenceDistance(disk, shape);
  const Real tol = kReferenceClosedFormRelative * r.scale;
  EXPECT_LE(std::fabs(r.distance - expected), tol)
      << what << ": reference " << str(r.distance) << " closed form " << str(expected);
  EXPECT_LE(r.certifiedGap(), tol) << what << ": certificate gap " << str(r.certifiedGap());
  EXPECT_LE(std::fabs((r.p_shape - r.p_disk).norm() - r.distance), tol) << what;
  EXPECT_LE(ref::distanceToDisk(r.p_disk, disk), tol) << what;
  EXPECT_LE(ref::distanceToShape(r.p_shape, shape), tol) << what;
}

const ref::Disk kUnitDisk = ref::makeDisk(1, M3::Identity(), V3::Zero());

TEST(ReferenceSelfCheck, DiskAboveABoxFaceIsTheHeight) {
  ref::Box box;
  box.side = V3(3, 2.5, 2);
  for (Real h : {Real(0), Real(1e-12), Real(0.25), Real(7)})
    expectReference(kUnitDisk, posed(box, M3::Identity(), V3(0.3, -0.2, 1 + h)), h, "parallel");
  // Disk tilted by 30 degrees about x, centre 2 above the face: its lowest
  // point is r sin(30) = 1/2 below the centre.
  const ref::Disk tilted = ref::makeDisk(1, rotX(M_PIl / 6), V3(0, 0, 2));
  expectReference(tilted, posed(box, M3::Identity(), V3(0.1, 0, -1)), Real(1.5), "tilted");
}

TEST(ReferenceSelfCheck, SphereOverTheDisk) {
  ref::Sphere s;
  s.radius = 0.5;
  expectReference(kUnitDisk, posed(s, M3::Identity(), V3(0, 0, 2)), Real(1.5), "over the centre");
  expectReference(kUnitDisk, posed(s, M3::Identity(), V3(3, 0, 0)), Real(1.5), "in the plane");
  expectReference(kUnitDisk, posed(s, M3::Identity(), V3(0, 4, 3)), std::sqrt(Real(18)) - 0.5L,
                  "beside the rim");
  expectReference(kUnitDisk, posed(s, M3::Identity(), V3(0.2, 0.1, 0.3)), Real(0), "overlapping");
}

TEST(ReferenceSelfCheck, EllipsoidWithEqualRadiiIsASphere) {
  fcl_disk_test::Random rng(5);
  for (int i = 0; i < 40; ++i) {
    const Real rho = rng.uniform(0.1, 2);
    const ref::Disk disk = ref::makeDisk(rng.uniform(0.2, 2), rng.rotation().cast<Real>(),
                                         rng.inBall(3).cast<Real>());
    ref::Ellipsoid e;
    e.radii = V3(rho, rho, rho);
    e = posed(e, rng.rotation().cast<Real>(), rng.inBall(3).cast<Real>());
    ref::Sphere s;
    s.radius = rho;
    s = posed(s, e.R, e.t);
    const Real expected = std::max<Real>(0, ref::distanceToDisk(e.t, disk) - rho);  // closed form
    expectReference(disk, e, expected, "ellipsoid");
    expectReference(disk, s, expected, "sphere");
  }
}

TEST(ReferenceSelfCheck, HalfspaceAndPlane) {
  // Long-double literals throughout: a double 0.8 is 0.8 only to 4e-17, above
  // this check's tolerance.
  // Tilted by theta, the disk's lowest point is r sin(theta) below its centre.
  const Real theta = 0.3L;
  const ref::Disk disk = ref::makeDisk(2, rotX(theta), V3(5, 6, 1));
  ref::Halfspace hs;
  hs.n = V3(0, 0, 1);
  hs.d = -0.5L;
  expectReference(disk, hs, 1.5L - 2 * std::sin(theta), "halfspace below");
  hs.d = 1;
  expectReference(disk, hs, Real(0), "halfspace through the centre");
  ref::Plane pl;
  pl.n = V3(0, 0, -1);  // z = 3, above
  pl.d = -3;
  expectReference(disk, pl, 2 - 2 * std::sin(theta), "plane above");
  pl.d = -1.5;
  expectReference(disk, pl, Real(0), "plane crossing");
  // A posed halfspace: local n = x, rotated onto z, moved up by 1: {z <= 0.2}.
  ref::Halfspace moved;
  moved.n = V3(1, 0, 0);
  moved.d = -0.8L;
  M3 x_to_z;
  x_to_z << 0, 0, -1, 0, 1, 0, 1, 0, 0;
  expectReference(disk, posed(moved, x_to_z, V3(0, 0, 1)), 0.8L - 2 * std::sin(theta), "posed");
}

TEST(ReferenceSelfCheck, CoaxialAndSideBySideCylinder) {
  ref::Cylinder cyl;
  cyl.radius = 0.7L;
  cyl.lz = 1.2L;
  expectReference(kUnitDisk, posed(cyl, M3::Identity(), V3(0, 0, 2)), 1.4L, "coaxial above");
  expectReference(kUnitDisk, posed(cyl, M3::Identity(), V3(2.5L, 0, 0.1L)), 0.8L, "side by side");
  // Axis along x, lying above the disk: the side is at height 2 - 0.7.
  M3 z_to_x;
  z_to_x << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  expectReference(kUnitDisk, posed(cyl, z_to_x, V3(0.2L, 0.3L, 2)), 1.3L, "lying above");
}

TEST(ReferenceSelfCheck, ConeApexAndBaseOverTheDisk) {
  ref::Cone cone;
  cone.radius = 0.8;
  cone.lz = 2;
  // Identity: base at z = H - 1 faces the disk.
  expectReference(kUnitDisk, posed(cone, M3::Identity(), V3(0, 0, 3)), Real(2), "base down");
  // Flipped: apex at H - 1, over the disk's centre.
  expectReference(kUnitDisk, posed(cone, rotX(M_PIl), V3(0, 0, 3)), Real(2), "apex down");
  expectReference(kUnitDisk, posed(cone, rotX(M_PIl), V3(0.3, -0.4, 1)), Real(0), "apex touching");
}

TEST(ReferenceSelfCheck, CapsuleTriangleAndConvexCube) {
  ref::Capsule cap;
  cap.radius = 0.25;
  cap.lz = 3;
  M3 z_to_x;
  z_to_x << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  expectReference(kUnitDisk, posed(cap, z_to_x, V3(0, 0.5, 1)), Real(0.75), "capsule lying above");
  ref::TriangleP tri;
  tri.a = V3(-2, -2, 0);
  tri.b = V3(3, -1, 0);
  tri.c = V3(0, 3, 0);
  expectReference(kUnitDisk, posed(tri, M3::Identity(), V3(0, 0, 0.6)), Real(0.6), "flat triangle");
  // Standing triangle with its lowest vertex over the disk.
  tri.a = V3(0.2, 0.3, 0);
  tri.b = V3(1, 0, 2);
  tri.c = V3(-1, 0.5, 2);
  expectReference(kUnitDisk, posed(tri, M3::Identity(), V3(0, 0, 0.9)), Real(0.9), "vertex down");
  // A cube as a Convex against the Box model, on random poses.
  ref::Convex cube;
  for (int k = 0; k < 8; ++k)
    cube.vertices.push_back(V3((k & 1) ? 0.5 : -0.5, (k & 2) ? 0.75 : -0.75, (k & 4) ? 0.25 : -0.25));
  cube.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  ref::Box box;
  box.side = V3(1, 1.5, 0.5);
  fcl_disk_test::Random rng(11);
  for (int i = 0; i < 30; ++i) {
    const ref::Disk disk = ref::makeDisk(rng.uniform(0.2, 2), rng.rotation().cast<Real>(),
                                         rng.inBall(2).cast<Real>());
    const M3 R = rng.rotation().cast<Real>();
    const V3 t = rng.inBall(2).cast<Real>();
    const ref::Result as_box = ref::referenceDistance(disk, posed(box, R, t));
    expectReference(disk, posed(cube, R, t), as_box.distance, "cube as convex vs box");
  }
}

}  // namespace
