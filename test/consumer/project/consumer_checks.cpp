// The checks every consumer binary runs (see consumer_checks.h). FCL only: no
// fcl_disk header, so a binary that never linked fcl_disk can compile this too.
#include "consumer_checks.h"

#include <dlfcn.h>
#include <link.h>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <utility>

namespace consumer {
namespace {

constexpr double kTolDouble = 1e-12;
constexpr double kTolFloat = 1e-5;

template <typename S>
constexpr double tolerance() {
  return std::is_same<S, float>::value ? kTolFloat : kTolDouble;
}
template <typename S>
const char* scalarName() {
  return std::is_same<S, float>::value ? "float" : "double";
}
const char* solverName(fcl::GJKSolverType solver) {
  return solver == fcl::GST_LIBCCD ? "GST_LIBCCD" : "GST_INDEP";
}

std::string fmt(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}
template <typename Derived>
std::string fmt(const Eigen::MatrixBase<Derived>& v) {
  std::ostringstream out;
  out << "(" << fmt(double(v(0))) << ", " << fmt(double(v(1))) << ", " << fmt(double(v(2)))
      << ")";
  return out.str();
}

/// Pose of a disk (or cylinder): centre c, local +Z along `normal`.
fcl::Transform3<double> pose(const fcl::Vector3<double>& centre,
                             const fcl::Vector3<double>& normal) {
  fcl::Transform3<double> X = fcl::Transform3<double>::Identity();
  X.linear() = Eigen::Quaterniond::FromTwoVectors(fcl::Vector3<double>::UnitZ(),
                                                   normal.normalized())
                   .toRotationMatrix();
  X.translation() = centre;
  return X;
}

fcl::Transform3<double> randomPose(std::mt19937& rng, double half_box) {
  std::uniform_real_distribution<double> position(-half_box, half_box);
  std::normal_distribution<double> gauss;
  Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
  q.normalize();
  fcl::Transform3<double> X = fcl::Transform3<double>::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() << position(rng), position(rng), position(rng);
  return X;
}

template <typename S>
fcl::Transform3<S> castPose(const fcl::Transform3<double>& X) {
  return X.template cast<S>();
}

// ---------------------------------------------------------------------------
// Query paths. Each runs one FCL entry point exactly as a planner would write it.

/// Distance and nearest points of one query.
template <typename S>
struct DistanceOutcome {
  S distance;
  fcl::Vector3<S> p1, p2;
  const fcl::CollisionGeometry<S>* o1;
  const fcl::CollisionGeometry<S>* o2;
};

enum class Path { objects, geometries };
const char* pathName(Path path) {
  return path == Path::objects ? "fcl::distance(&o1, &o2, req, res)"
                               : "fcl::distance(g1, tf1, g2, tf2, req, res)";
}
const char* collidePathName(Path path) {
  return path == Path::objects ? "fcl::collide(&o1, &o2, req, res)"
                               : "fcl::collide(g1, tf1, g2, tf2, req, res)";
}

template <typename S>
DistanceOutcome<S> queryDistance(Path path, fcl::GJKSolverType solver,
                                 const std::shared_ptr<fcl::CollisionGeometry<S>>& g1,
                                 const fcl::Transform3<S>& X1,
                                 const std::shared_ptr<fcl::CollisionGeometry<S>>& g2,
                                 const fcl::Transform3<S>& X2) {
  fcl::DistanceRequest<S> request;
  request.gjk_solver_type = solver;
  request.enable_nearest_points = true;
  fcl::DistanceResult<S> result;
  if (path == Path::objects) {
    fcl::CollisionObject<S> o1(g1, X1), o2(g2, X2);
    fcl::distance(&o1, &o2, request, result);
  } else {
    fcl::distance(g1.get(), X1, g2.get(), X2, request, result);
  }
  return {result.min_distance, result.nearest_points[0], result.nearest_points[1], result.o1,
          result.o2};
}

template <typename S>
fcl::CollisionResult<S> queryCollide(Path path, fcl::GJKSolverType solver,
                                     const std::shared_ptr<fcl::CollisionGeometry<S>>& g1,
                                     const fcl::Transform3<S>& X1,
                                     const std::shared_ptr<fcl::CollisionGeometry<S>>& g2,
                                     const fcl::Transform3<S>& X2, bool enable_contact) {
  fcl::CollisionRequest<S> request;
  request.gjk_solver_type = solver;
  request.enable_contact = enable_contact;
  fcl::CollisionResult<S> result;
  if (path == Path::objects) {
    fcl::CollisionObject<S> o1(g1, X1), o2(g2, X2);
    fcl::collide(&o1, &o2, request, result);
  } else {
    fcl::collide(g1.get(), X1, g2.get(), X2, request, result);
  }
  return result;
}

// ---------------------------------------------------------------------------
// Real cylinders: FCL's own answers, before and after fcl_disk.

using FlatMakerD = std::function<std::shared_ptr<fcl::CollisionGeometry<double>>(double)>;
using FlatMakerF = std::function<std::shared_ptr<fcl::CollisionGeometry<float>>(float)>;

struct CylinderCase {
  std::string name;
  bool flat1, flat2;  ///< shape i is the "flat" one (plain Cylinder(r, 0) or a Disk)
  double r1, lz1;
  fcl::Transform3<double> X1;
  double r2, lz2;
  fcl::Transform3<double> X2;
};

std::vector<CylinderCase> cylinderCases() {
  const double s5 = std::sqrt(5.0);
  std::vector<CylinderCase> cases;
  cases.push_back({"thick/thick apart", false, false, 0.5, 1.0,
                   pose({0, 0, 0}, {0.2, -0.3, 1}), 0.3, 0.8, pose({1.4, 0.3, 0.5}, {1, 1, 0.2})});
  cases.push_back({"thick/thick overlapping", false, false, 0.5, 1.0,
                   pose({0, 0, 0}, {0, 0, 1}), 0.3, 0.8, pose({0.6, 0.1, 0.2}, {1, 0, 0.3})});
  // Plain fcl::Cylinder(1, 0) pair at counterexample A: a real Cylinder, not a Disk.
  cases.push_back({"flat/flat at counterexample A", true, true, 1.0, 0.0,
                   pose({0, 0, 0}, {0, 0, 1}), 1.0, 0.0, pose({0, 0, -0.5}, {0, 1 / s5, 2 / s5})});
  cases.push_back({"flat/thick apart", true, false, 1.0, 0.0, pose({0, 0, 0}, {0, 0, 1}), 0.4,
                   0.6, pose({0.3, 0.2, 1.0}, {0.5, 0, 1})});
  cases.push_back({"thick/flat apart", false, true, 0.4, 0.6,
                   pose({0.3, -0.2, -1.1}, {0, 0.5, 1}), 1.0, 0.0, pose({0, 0, 0}, {0.1, 0, 1})});
  cases.push_back({"flat/thick overlapping", true, false, 1.0, 0.0, pose({0, 0, 0}, {0, 0, 1}),
                   0.3, 1.0, pose({0.5, 0, 0}, {0, 0, 1})});
  return cases;
}

template <typename S>
void cylinderQueriesForScalar(const CylinderCase& c,
                              const std::function<std::shared_ptr<fcl::CollisionGeometry<S>>(S)>&
                                  make_flat,
                              std::vector<LabeledValue>& out) {
  auto make = [&](bool flat, double r, double lz) -> std::shared_ptr<fcl::CollisionGeometry<S>> {
    if (flat) return make_flat(S(r));
    return std::make_shared<fcl::Cylinder<S>>(S(r), S(lz));
  };
  const auto g1 = make(c.flat1, c.r1, c.lz1);
  const auto g2 = make(c.flat2, c.r2, c.lz2);
  const auto X1 = castPose<S>(c.X1), X2 = castPose<S>(c.X2);
  const double tol = tolerance<S>();
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    for (auto path : {Path::objects, Path::geometries}) {
      const std::string prefix =
          c.name + ": " + scalarName<S>() + " " + solverName(solver) + " ";
      const auto d = queryDistance<S>(path, solver, g1, X1, g2, X2);
      const std::string dl = prefix + pathName(path);
      out.push_back({dl + " distance", double(d.distance), tol});
      for (int k = 0; k < 3; ++k) {
        out.push_back({dl + " p1[" + std::to_string(k) + "]", double(d.p1[k]), tol});
        out.push_back({dl + " p2[" + std::to_string(k) + "]", double(d.p2[k]), tol});
      }
      const auto r = queryCollide<S>(path, solver, g1, X1, g2, X2, /*enable_contact=*/false);
      out.push_back({prefix + collidePathName(path) + " numContacts", double(r.numContacts()), 0});
    }
  }
}

std::vector<LabeledValue> cylinderQueries(const FlatMakerD& make_flat_d,
                                          const FlatMakerF& make_flat_f, bool include_flat_flat) {
  std::vector<LabeledValue> out;
  for (const auto& c : cylinderCases()) {
    if (c.flat1 && c.flat2 && !include_flat_flat) continue;
    cylinderQueriesForScalar<double>(c, make_flat_d, out);
    cylinderQueriesForScalar<float>(c, make_flat_f, out);
  }
  return out;
}

std::shared_ptr<fcl::CollisionGeometry<double>> plainFlatCylinderD(double r) {
  return std::make_shared<fcl::Cylinder<double>>(r, 0.0);
}
std::shared_ptr<fcl::CollisionGeometry<float>> plainFlatCylinderF(float r) {
  return std::make_shared<fcl::Cylinder<float>>(r, 0.0f);
}

int compareWithBaseline(const std::string& what, const std::vector<LabeledValue>& now,
                        const CylinderBaseline& baseline) {
  std::map<std::string, const LabeledValue*> before;
  for (const auto& v : baseline.values) before[v.label] = &v;
  int failures = 0;
  std::size_t compared = 0;
  double worst = 0;
  for (const auto& v : now) {
    auto it = before.find(v.label);
    if (it == before.end()) {
      failures += report(false, what + ": no baseline value for " + v.label);
      continue;
    }
    ++compared;
    const double diff = std::abs(v.value - it->second->value);
    const bool ok = diff <= v.tolerance || (std::isnan(v.value) && std::isnan(it->second->value));
    worst = std::max(worst, diff);
    if (!ok) {
      failures += report(false, what + ": " + v.label + ": got " + fmt(v.value) +
                                    ", FCL's answer before any Disk existed " +
                                    fmt(it->second->value));
    }
  }
  if (failures == 0) {
    report(compared > 0, what + ": " + std::to_string(compared) +
                             " values equal FCL's answers computed before any Disk existed "
                             "(max |diff| " + fmt(worst) + ")");
    if (compared == 0) ++failures;
  }
  return failures;
}

// ---------------------------------------------------------------------------
// Disk pairs: every query path must return exactDiskDistance's answer.

struct DiskCase {
  std::string name;
  double r1;
  fcl::Transform3<double> X1;
  double r2;
  fcl::Transform3<double> X2;
};

std::vector<DiskCase> diskCases(const DiskApi& api) {
  const double s5 = std::sqrt(5.0), s2 = std::sqrt(2.0);
  std::vector<DiskCase> cases;
  const auto I = pose({0, 0, 0}, {0, 0, 1});
  cases.push_back({"counterexample A", 1.0, I, 1.0, pose({0, 0, -0.5}, {0, 1 / s5, 2 / s5})});
  cases.push_back({"counterexample B", 1.0, pose({0, 0, 0}, {0, 1, 0}), 1.0,
                   pose({-1.5, 0, 0}, {1 / s2, 0, 1 / s2})});
  cases.push_back({"face of 1 / rim of 2", 1.0, I, 0.5, pose({0.2, 0.1, 0.8}, {1, 0, 3})});
  cases.push_back({"counterexample A, 1e-7 apart", 1.0, I, 1.0,
                   pose({0, 0, -1 / s5 - 1e-7}, {0, 1 / s5, 2 / s5})});
  cases.push_back({"counterexample A raised 0.1 (crossing)", 1.0, I, 1.0,
                   pose({0, 0, -0.4}, {0, 1 / s5, 2 / s5})});
  cases.push_back({"perpendicular through the centre (crossing)", 1.0, I, 0.5,
                   pose({0.3, 0, 0}, {1, 0, 0})});
  // Random separated pairs (fixed seed), mostly rim-rim.
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> radius(0.2, 1.5);
  int made = 0;
  while (made < 4) {
    const double r1 = radius(rng), r2 = radius(rng);
    const auto X1 = randomPose(rng, 1.5), X2 = randomPose(rng, 1.5);
    if (api.exact_d(r1, X1, r2, X2).distance < 1e-3) continue;
    cases.push_back({"random pair " + std::to_string(++made), r1, X1, r2, X2});
  }
  return cases;
}

template <typename S>
ExactAnswer<S> exactAnswer(const DiskApi& api, S r1, const fcl::Transform3<S>& X1, S r2,
                           const fcl::Transform3<S>& X2) {
  if constexpr (std::is_same<S, float>::value) {
    return api.exact_f(r1, X1, r2, X2);
  } else {
    return api.exact_d(r1, X1, r2, X2);
  }
}
template <typename S>
IntersectAnswer<S> intersectAnswer(const DiskApi& api, S r1, const fcl::Transform3<S>& X1, S r2,
                                   const fcl::Transform3<S>& X2) {
  if constexpr (std::is_same<S, float>::value) {
    return api.intersect_f(r1, X1, r2, X2);
  } else {
    return api.intersect_d(r1, X1, r2, X2);
  }
}
template <typename S>
std::shared_ptr<fcl::CollisionGeometry<S>> makeDisk(const DiskApi& api, S r) {
  if constexpr (std::is_same<S, float>::value) {
    return api.make_disk_f(r);
  } else {
    return api.make_disk_d(r);
  }
}

template <typename S>
int checkDiskCase(const DiskCase& c, const DiskApi& api) {
  int failures = 0;
  const S r1 = S(c.r1), r2 = S(c.r2);
  const auto X1 = castPose<S>(c.X1), X2 = castPose<S>(c.X2);
  const auto g1 = makeDisk<S>(api, r1), g2 = makeDisk<S>(api, r2);
  const auto exact = exactAnswer<S>(api, r1, X1, r2, X2);
  // The swapped query is answered by exactDiskDistance on the swapped arguments
  // (its nearest points are not bitwise symmetric under the swap).
  const auto exact_swapped = exactAnswer<S>(api, r2, X2, r1, X1);
  const auto hit = intersectAnswer<S>(api, r1, X1, r2, X2);
  const double tol = tolerance<S>();
  const std::string head = c.name + " [" + scalarName<S>() + "] ";

  // Distance, both orders of the pair: points must follow the objects.
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    for (auto path : {Path::objects, Path::geometries}) {
      for (bool swapped : {false, true}) {
        const auto d = swapped ? queryDistance<S>(path, solver, g2, X2, g1, X1)
                               : queryDistance<S>(path, solver, g1, X1, g2, X2);
        const ExactAnswer<S>& want = swapped ? exact_swapped : exact;
        const fcl::Vector3<S>& want1 = want.p1;
        const fcl::Vector3<S>& want2 = want.p2;
        const double err = std::abs(double(d.distance) - double(want.distance));
        const double err1 = (d.p1 - want1).norm(), err2 = (d.p2 - want2).norm();
        const bool ok = err <= tol && err1 <= tol && err2 <= tol;
        std::string what = head + pathName(path) + " " + solverName(solver) +
                           (swapped ? " (pair swapped)" : "") + ": distance " +
                           fmt(double(d.distance)) + " vs exactDiskDistance " +
                           fmt(double(want.distance));
        if (!ok) {
          what += " |diff| " + fmt(err) + ", p1 " + fmt(d.p1) + " vs " + fmt(want1) + ", p2 " +
                  fmt(d.p2) + " vs " + fmt(want2) + " (tolerance " + fmt(tol) + ")";
        }
        failures += report(ok, what);
      }
    }
  }

  // Collision, with contact: must be intersectDisks' answer.
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    for (auto path : {Path::objects, Path::geometries}) {
      const auto r = queryCollide<S>(path, solver, g1, X1, g2, X2, /*enable_contact=*/true);
      bool ok = r.isCollision() == hit.intersect;
      std::string what = head + collidePathName(path) + " " + solverName(solver) +
                         ": isCollision " + (r.isCollision() ? "true" : "false") +
                         " vs intersectDisks " + (hit.intersect ? "true" : "false");
      if (ok && hit.intersect) {
        ok = r.numContacts() == 1;
        if (ok) {
          const auto& contact = r.getContact(0);
          const double e_pos = (contact.pos - hit.pos).norm();
          const double e_normal = (contact.normal - hit.normal).norm();
          const double e_depth = std::abs(double(contact.penetration_depth) - double(hit.depth));
          ok = e_pos <= tol && e_normal <= tol && e_depth <= tol && contact.o1 == g1.get() &&
               contact.o2 == g2.get();
          what += ", contact pos " + fmt(contact.pos) + " normal " + fmt(contact.normal) +
                  " depth " + fmt(double(contact.penetration_depth));
          if (!ok) {
            what += " vs intersectDisks pos " + fmt(hit.pos) + " normal " + fmt(hit.normal) +
                    " depth " + fmt(double(hit.depth)) + " (o1/o2 " +
                    (contact.o1 == g1.get() && contact.o2 == g2.get() ? "right" : "WRONG") + ")";
          }
        } else {
          what += ", numContacts " + std::to_string(r.numContacts()) + " (want 1)";
        }
      }
      failures += report(ok, what);
    }
  }
  // The two fcl_disk solvers must agree with each other on this pair.
  failures += report((exact.distance == S(0)) == hit.intersect,
                     head + "consistency: exactDiskDistance " + fmt(double(exact.distance)) +
                         ", intersectDisks " + (hit.intersect ? "true" : "false"));
  return failures;
}

/// Known values, so a wrong exactDiskDistance cannot make the checks vacuous, and a
/// proof that FCL's GJK on a flat cylinder gives a measurably different answer.
int checkReferenceValues(const DiskApi& api) {
  int failures = 0;
  const double s5 = std::sqrt(5.0), s2 = std::sqrt(2.0);
  const auto I = pose({0, 0, 0}, {0, 0, 1});
  const auto XA = pose({0, 0, -0.5}, {0, 1 / s5, 2 / s5});
  const double a = api.exact_d(1.0, I, 1.0, XA).distance;
  const double a_true = 0.5 - 1 / s5;
  failures += report(std::abs(a - a_true) <= kTolDouble,
                     "reference: exactDiskDistance on counterexample A = " + fmt(a) +
                         ", 0.5 - 1/sqrt5 = " + fmt(a_true));
  const double b = api.exact_d(1.0, pose({0, 0, 0}, {0, 1, 0}), 1.0,
                               pose({-1.5, 0, 0}, {1 / s2, 0, 1 / s2}))
                       .distance;
  failures += report(std::abs(b - 0.062393) <= 1e-6,
                     "reference: exactDiskDistance on counterexample B = " + fmt(b) +
                         " (facts.md: 0.062393)");
  // FCL's GJK on the same pair as plain Cylinder(1, 0): it is what an unhooked
  // dispatch would return, and must be distinguishable at our tolerance.
  auto cyl = std::make_shared<fcl::Cylinder<double>>(1.0, 0.0);
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    const auto d = queryDistance<double>(Path::objects, solver, cyl, I, cyl, XA);
    const double gap = std::abs(d.distance - a_true) +
                       std::max((d.p1 - api.exact_d(1.0, I, 1.0, XA).p1).norm(),
                                (d.p2 - api.exact_d(1.0, I, 1.0, XA).p2).norm());
    failures += report(gap > 100 * kTolDouble,
                       std::string("reference: FCL GJK (") + solverName(solver) +
                           ") on plain Cylinder(1, 0) at counterexample A gives " +
                           fmt(d.distance) + ", off the exact answer by " + fmt(gap) +
                           " > 100 x tolerance: the disk checks can tell GJK from fcl_disk");
  }
  return failures;
}

// ---------------------------------------------------------------------------
// Broadphase: DynamicAABBTreeCollisionManager with FCL's default callbacks.

struct Scene {
  std::vector<double> radii;
  std::vector<fcl::Transform3<double>> poses;
  std::vector<std::shared_ptr<fcl::CollisionGeometry<double>>> geometries;
  std::vector<std::unique_ptr<fcl::CollisionObject<double>>> objects;
  std::map<const fcl::CollisionGeometry<double>*, int> index;
};

/// `count` random disks in a cube of half-width `half_box`; no pair is closer than
/// 1e-6 without intersecting (so the answers are not decided by rounding), and with
/// `disjoint` no pair intersects.
Scene makeScene(const DiskApi& api, std::uint32_t seed, int count, double half_box,
                bool disjoint) {
  Scene scene;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> radius(0.2, 0.6);
  while (int(scene.radii.size()) < count) {
    const double r = radius(rng);
    const auto X = randomPose(rng, half_box);
    bool ambiguous = false;
    for (std::size_t j = 0; j < scene.radii.size() && !ambiguous; ++j) {
      const double d = api.exact_d(r, X, scene.radii[j], scene.poses[j]).distance;
      ambiguous = disjoint ? d < 1e-3 : (d > 0 && d < 1e-6);
    }
    if (ambiguous) continue;
    scene.radii.push_back(r);
    scene.poses.push_back(X);
  }
  for (int i = 0; i < count; ++i) {
    scene.geometries.push_back(api.make_disk_d(scene.radii[i]));
    scene.objects.push_back(
        std::make_unique<fcl::CollisionObject<double>>(scene.geometries[i], scene.poses[i]));
    scene.index[scene.geometries[i].get()] = i;
  }
  return scene;
}

int checkBroadphaseDistance(const DiskApi& api) {
  int failures = 0;
  Scene scene = makeScene(api, 7, 50, 3.0, /*disjoint=*/true);
  const int n = int(scene.objects.size());
  // Exact minimum over all pairs.
  double exact_min = std::numeric_limits<double>::infinity();
  std::pair<int, int> exact_arg{-1, -1};
  double second = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const double d = api.exact_d(scene.radii[i], scene.poses[i], scene.radii[j],
                                   scene.poses[j]).distance;
      if (d < exact_min) {
        second = exact_min;
        exact_min = d;
        exact_arg = {i, j};
      } else {
        second = std::min(second, d);
      }
    }
  }
  const auto exact_pair = api.exact_d(scene.radii[exact_arg.first], scene.poses[exact_arg.first],
                                      scene.radii[exact_arg.second],
                                      scene.poses[exact_arg.second]);
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    const std::string head = std::string("broadphase distance (") + std::to_string(n) +
                             " disks, " + solverName(solver) + "): ";
    // Brute force with plain fcl::distance.
    double brute_min = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        fcl::DistanceRequest<double> request;
        request.gjk_solver_type = solver;
        fcl::DistanceResult<double> result;
        fcl::distance(scene.objects[i].get(), scene.objects[j].get(), request, result);
        brute_min = std::min(brute_min, result.min_distance);
      }
    }
    failures += report(std::abs(brute_min - exact_min) <= kTolDouble,
                       head + "pairwise fcl::distance minimum " + fmt(brute_min) +
                           " vs exactDiskDistance minimum " + fmt(exact_min));

    fcl::DynamicAABBTreeCollisionManager<double> manager;
    std::vector<fcl::CollisionObject<double>*> objects;
    for (auto& o : scene.objects) objects.push_back(o.get());
    manager.registerObjects(objects);
    manager.setup();
    fcl::DefaultDistanceData<double> data;
    data.request.gjk_solver_type = solver;
    data.request.enable_nearest_points = true;
    manager.distance(&data, fcl::DefaultDistanceFunction<double>);
    const double got = data.result.min_distance;
    failures += report(std::abs(got - brute_min) <= kTolDouble,
                       head + "DefaultDistanceFunction minimum " + fmt(got) +
                           " vs pairwise fcl::distance minimum " + fmt(brute_min));
    // Which pair, and its nearest points (the minimum is unique by a margin).
    failures += report(exact_min > 0 && second - exact_min > 1e-9,
                       head + "scene: disjoint disks, closest pair unique (distance " +
                           fmt(exact_min) + ", next " + fmt(second) + ")");
    if (second - exact_min > 1e-9) {
      auto i1 = scene.index.find(data.result.o1), i2 = scene.index.find(data.result.o2);
      const bool known = i1 != scene.index.end() && i2 != scene.index.end();
      bool ok = known && std::minmax(i1->second, i2->second) ==
                             std::minmax(exact_arg.first, exact_arg.second);
      std::string what = head + "closest pair " +
                         (known ? std::to_string(i1->second) + "-" + std::to_string(i2->second)
                                : std::string("unknown geometries")) +
                         " vs exact " + std::to_string(exact_arg.first) + "-" +
                         std::to_string(exact_arg.second);
      if (ok) {
        const bool in_order = i1->second == exact_arg.first;
        const auto& w1 = in_order ? exact_pair.p1 : exact_pair.p2;
        const auto& w2 = in_order ? exact_pair.p2 : exact_pair.p1;
        const double e = std::max((data.result.nearest_points[0] - w1).norm(),
                                  (data.result.nearest_points[1] - w2).norm());
        ok = e <= kTolDouble;
        what += ", nearest points off by " + fmt(e);
      }
      failures += report(ok, what);
    }
  }
  return failures;
}

int checkBroadphaseCollision(const DiskApi& api) {
  int failures = 0;
  Scene scene = makeScene(api, 11, 50, 1.5, /*disjoint=*/false);
  const int n = int(scene.objects.size());
  using PairSet = std::set<std::pair<int, int>>;
  PairSet exact_pairs;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (api.intersect_d(scene.radii[i], scene.poses[i], scene.radii[j], scene.poses[j])
              .intersect)
        exact_pairs.insert({i, j});
  const bool nontrivial = !exact_pairs.empty() && int(exact_pairs.size()) < n * (n - 1) / 2;
  failures += report(nontrivial, "broadphase collision scene: " +
                                     std::to_string(exact_pairs.size()) +
                                     " intersecting pairs among " + std::to_string(n) + " disks");
  auto show = [](const PairSet& s) {
    std::string out;
    for (const auto& p : s) out += " " + std::to_string(p.first) + "-" + std::to_string(p.second);
    return out;
  };
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    const std::string head = std::string("broadphase collision (") + std::to_string(n) +
                             " disks, " + solverName(solver) + "): ";
    PairSet brute_pairs;
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        fcl::CollisionRequest<double> request;
        request.gjk_solver_type = solver;
        fcl::CollisionResult<double> result;
        fcl::collide(scene.objects[i].get(), scene.objects[j].get(), request, result);
        if (result.isCollision()) brute_pairs.insert({i, j});
      }
    }
    failures += report(brute_pairs == exact_pairs,
                       head + "pairwise fcl::collide finds " + std::to_string(brute_pairs.size()) +
                           " pairs, intersectDisks " + std::to_string(exact_pairs.size()) +
                           (brute_pairs == exact_pairs
                                ? std::string(", the same ones")
                                : ": fcl::collide" + show(brute_pairs) + " vs" +
                                      show(exact_pairs)));

    fcl::DynamicAABBTreeCollisionManager<double> manager;
    std::vector<fcl::CollisionObject<double>*> objects;
    for (auto& o : scene.objects) objects.push_back(o.get());
    manager.registerObjects(objects);
    manager.setup();
    fcl::DefaultCollisionData<double> data;
    data.request.gjk_solver_type = solver;
    data.request.num_max_contacts = 100000;  // every pair, not just the first
    manager.collide(&data, fcl::DefaultCollisionFunction<double>);
    PairSet broad_pairs;
    bool all_known = true;
    for (std::size_t k = 0; k < data.result.numContacts(); ++k) {
      const auto& contact = data.result.getContact(k);
      auto i1 = scene.index.find(contact.o1), i2 = scene.index.find(contact.o2);
      if (i1 == scene.index.end() || i2 == scene.index.end()) {
        all_known = false;
        continue;
      }
      broad_pairs.insert(std::minmax(i1->second, i2->second));
    }
    const bool ok = all_known && broad_pairs == brute_pairs &&
                    data.result.numContacts() == broad_pairs.size();
    failures += report(ok, head + "DefaultCollisionFunction finds " +
                               std::to_string(broad_pairs.size()) + " pairs (" +
                               std::to_string(data.result.numContacts()) + " contacts)" +
                               (ok ? std::string(", the same as pairwise fcl::collide")
                                   : ": broadphase" + show(broad_pairs) + " vs pairwise" +
                                         show(brute_pairs) +
                                         (all_known ? "" : " (contacts with unknown geometry)")));
  }
  return failures;
}

std::string fileName(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string objectOf(const void* address) {
  Dl_info info{};
  if (!dladdr(address, &info) || !info.dli_fname) return "<unknown>";
  return fileName(info.dli_fname);
}

}  // namespace

// ---------------------------------------------------------------------------

int report(bool ok, const std::string& what) {
  std::printf("[%s] %s\n", ok ? "PASS" : "FAIL", what.c_str());
  std::fflush(stdout);
  return ok ? 0 : 1;
}

CylinderBaseline computeCylinderBaseline() {
  return {cylinderQueries(plainFlatCylinderD, plainFlatCylinderF, /*include_flat_flat=*/true)};
}

std::vector<std::string> loadedObjects() {
  std::vector<std::string> names;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* data) -> int {
        static_cast<std::vector<std::string>*>(data)->push_back(
            info->dlpi_name ? info->dlpi_name : "");
        return 0;
      },
      &names);
  return names;
}

int loadedIndex(const std::vector<std::string>& objects, const std::string& prefix) {
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (fileName(objects[i]).rfind(prefix, 0) == 0) return int(i);
  }
  return -1;
}

void printBindings(const std::string& label) {
  const auto objects = loadedObjects();
  const int fcl = loadedIndex(objects, "libfcl.so");
  const int disk = loadedIndex(objects, "libfcl_disk.so");
  using DistanceFn = double (*)(const fcl::CollisionObject<double>*,
                                const fcl::CollisionObject<double>*,
                                const fcl::DistanceRequest<double>&, fcl::DistanceResult<double>&);
  using CollideFn = std::size_t (*)(const fcl::CollisionObject<double>*,
                                    const fcl::CollisionObject<double>*,
                                    const fcl::CollisionRequest<double>&,
                                    fcl::CollisionResult<double>&);
  const DistanceFn distance_fn = &fcl::distance<double>;
  const CollideFn collide_fn = &fcl::collide<double>;
  std::printf("[info] %s: link map: libfcl at %d, libfcl_disk at %d (%s), plain "
              "fcl::distance<double> binds to %s, fcl::collide<double> to %s\n",
              label.c_str(), fcl, disk,
              disk < 0 ? "not loaded" : (disk < fcl ? "fcl_disk first" : "fcl first"),
              objectOf(reinterpret_cast<const void*>(distance_fn)).c_str(),
              objectOf(reinterpret_cast<const void*>(collide_fn)).c_str());
  std::fflush(stdout);
}

/// A Disk against a real fcl::Cylinder, a Box and a Halfspace, both argument
/// orders, both solvers, objects and geometries: the answer of fcl_disk's
/// diskShapeDistance(), so the pair reached fcl_disk in this binary's link mode
/// (FCL's own answer on the flat cylinder is GJK's, and against a Halfspace it
/// crashes with libccd).
template <typename S>
int checkDiskVsShapes(const DiskApi& api) {
  int failures = 0, compared = 0;
  const double tol = tolerance<S>();
  struct ShapeCase {
    std::string name;
    double r;
    fcl::Transform3<double> X_WD;
    std::shared_ptr<fcl::CollisionGeometry<S>> shape;
    fcl::Transform3<double> X_WS;
  };
  std::vector<ShapeCase> cases;
  for (const auto& c : cylinderCases()) {
    if (c.flat1 == c.flat2) continue;  // exactly one flat shape: it becomes the Disk
    const bool disk_first = c.flat1;
    cases.push_back({"real fcl::Cylinder, " + c.name, disk_first ? c.r1 : c.r2,
                     disk_first ? c.X1 : c.X2,
                     std::make_shared<fcl::Cylinder<S>>(S(disk_first ? c.r2 : c.r1),
                                                        S(disk_first ? c.lz2 : c.lz1)),
                     disk_first ? c.X2 : c.X1});
  }
  cases.push_back({"Box, apart", 0.5, pose({0, 0, 0}, {0.2, 0.1, 1}),
                   std::make_shared<fcl::Box<S>>(S(0.4), S(0.3), S(0.2)),
                   pose({0.3, 0.5, 0.8}, {1, 0.3, 0.2})});
  cases.push_back({"Box, overlapping", 0.5, pose({0, 0, 0}, {0, 0, 1}),
                   std::make_shared<fcl::Box<S>>(S(0.4), S(0.3), S(0.2)),
                   pose({0.4, 0.1, 0.05}, {0, 0.3, 1})});
  cases.push_back({"Halfspace ground, apart", 0.5, pose({0.1, 0.2, 1.0}, {0.3, 0, 1}),
                   std::make_shared<fcl::Halfspace<S>>(fcl::Vector3<S>(0, 0, 1), S(0)),
                   pose({0, 0, 0}, {0, 0, 1})});
  cases.push_back({"Halfspace ground, crossing", 0.5, pose({0.1, 0.2, 0.1}, {1, 0, 0.2}),
                   std::make_shared<fcl::Halfspace<S>>(fcl::Vector3<S>(0, 0, 1), S(0)),
                   pose({0, 0, 0}, {0, 0, 1})});
  for (const auto& c : cases) {
    const auto X_WD = castPose<S>(c.X_WD);
    const auto X_WS = castPose<S>(c.X_WS);
    std::shared_ptr<fcl::CollisionGeometry<S>> disk;
    ExactAnswer<S> expected;
    if constexpr (std::is_same<S, float>::value) {
      disk = api.make_disk_f(S(c.r));
      expected = api.disk_shape_f(S(c.r), X_WD, *c.shape, X_WS);
    } else {
      disk = api.make_disk_d(S(c.r));
      expected = api.disk_shape_d(S(c.r), X_WD, *c.shape, X_WS);
    }
    for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
      for (auto path : {Path::objects, Path::geometries}) {
        for (bool disk_is_o1 : {true, false}) {
          const auto d = disk_is_o1 ? queryDistance<S>(path, solver, disk, X_WD, c.shape, X_WS)
                                    : queryDistance<S>(path, solver, c.shape, X_WS, disk, X_WD);
          const fcl::Vector3<S>& on_disk = disk_is_o1 ? d.p1 : d.p2;
          const fcl::Vector3<S>& on_shape = disk_is_o1 ? d.p2 : d.p1;
          const bool ok = std::abs(double(d.distance) - double(expected.distance)) <= tol &&
                          double((on_disk - expected.p1).norm()) <= tol &&
                          double((on_shape - expected.p2).norm()) <= tol;
          ++compared;
          if (!ok) {
            failures += report(
                false, "Disk vs " + c.name + ": " + scalarName<S>() + " " + solverName(solver) +
                           " " + pathName(path) + (disk_is_o1 ? " (disk first)" : " (disk second)") +
                           ": got " + fmt(double(d.distance)) + " " + fmt(on_disk) + " " +
                           fmt(on_shape) + ", diskShapeDistance " +
                           fmt(double(expected.distance)) + " " + fmt(expected.p1) + " " +
                           fmt(expected.p2));
          }
        }
      }
    }
  }
  if (failures == 0) {
    report(compared > 0, std::string("Disk vs real fcl::Cylinder, Box, Halfspace (") +
                             scalarName<S>() + "): " + std::to_string(compared) +
                             " queries answered by diskShapeDistance");
    if (compared == 0) ++failures;
  }
  return failures;
}

int runAllChecks(const std::string& label, const DiskApi& api, const CylinderBaseline& baseline,
                 bool float_tables_shared) {
  std::printf("==== %s (disks from %s) ====\n", label.c_str(), api.provider);
  std::fflush(stdout);
  printBindings(label);
  int failures = 0;
  failures += checkReferenceValues(api);
  for (const auto& c : diskCases(api)) {
    failures += checkDiskCase<double>(c, api);
    // A host that neither links fcl_disk nor exports its symbols keeps private
    // copies of FCL's float tables, which no library can reach (docs/fcl_hook.md).
    if (float_tables_shared) failures += checkDiskCase<float>(c, api);
  }
  if (!float_tables_shared) {
    std::printf("  float disk queries by this code: not checked (its float tables are private; "
                "documented limitation)\n");
  }
  // Real cylinders keep FCL's own answers: plain Cylinder pairs (flat ones too) ...
  failures += compareWithBaseline(
      "real fcl::Cylinder pairs",
      cylinderQueries(plainFlatCylinderD, plainFlatCylinderF, /*include_flat_flat=*/true),
      baseline);
  // ... and a Disk against a real cylinder (or a box, a halfspace) is fcl_disk's
  // answer, on every path.
  failures += checkDiskVsShapes<double>(api);
  if (float_tables_shared) failures += checkDiskVsShapes<float>(api);
  failures += checkBroadphaseDistance(api);
  failures += checkBroadphaseCollision(api);
  std::printf("==== %s: %d failure(s) ====\n", label.c_str(), failures);
  std::fflush(stdout);
  return failures;
}

}  // namespace consumer
