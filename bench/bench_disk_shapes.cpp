// Google Benchmark suite for disk-vs-primitive queries (built with
// -DFCL_DISK_BUILD_BENCHMARKS=ON; not part of the test run).
//
// For every shape X of bench/disk_shape_cases.h (sphere, box, capsule, cylinder,
// cone, ellipsoid, convex8, convex40, halfspace, plane, triangle) a fixed pool of
// kPoolSize random cases (disk radius 0.5, shapes ~0.5, centres in the unit
// ball, random rotations, separated and overlapping mixed); every benchmark
// cycles through the pool, one case per iteration, with a fresh request and
// result each time. Names: disk_shapes/<shape>/<variant>/<scalar>, variants:
//   distance_disk_<libccd|indep>      fcl::distance(Disk(r), X) on CollisionObjects,
//                                     request.gjk_solver_type as named (float and
//                                     double): whatever answers a Disk in this
//                                     build, fcl_disk's solver or FCL's GJK on the
//                                     flat cylinder;
//   distance_swapped_libccd           fcl::distance(X, Disk(r)): the other order;
//   distance_sphere_<libccd|indep>    FCL's own fcl::distance(Sphere(r), X), same
//                                     poses: the baseline for a disk;
//   distance_flat_cylinder_<libccd|indep>
//                                     FCL on a real fcl::Cylinder(r, 0), same
//                                     poses: GJK on the flat cylinder, what a disk
//                                     got before fcl_disk had its own solvers
//                                     (fcl_disk leaves real cylinders to FCL);
//   collide_disk, collide_sphere      fcl::collide(Disk(r) / Sphere(r), X), default
//                                     CollisionRequest (one contact, no contact
//                                     points);
//   direct                            fcl_disk::diskShapeDistance called directly
//                                     (float and double): distance_disk minus
//                                     direct = the cost of going through FCL.
// Counters: overlap = fraction of iterations answering "overlap" (collide true,
// or distance <= 1e-9 in double, 1e-5 in float, the cases being of size ~1: GJK
// reports overlap as -1, an iterative solver may stop at 1e-16 in double or 1e-8
// in float): equal across variants on the same poses, a check that they answer
// the same question.
//
// Skipped variants (shown as errors in the output, with the reason): before
// registering, every variant runs once over its whole pool in a forked child
// (probeInChild); a variant that crashes, hangs, leaves the distance unset or
// makes FCL print "not supported" is not timed. FCL 0.7 has no distance or
// collision function for TriangleP against any shape (Sphere and Cylinder
// included), and Cylinder(r, 0) against Halfspace or Plane segfaults under
// libccd.
//
// Hull sizes: disk_convex_hulls/<N>/<variant>/double, one Convex of N random
// points on the sphere of radius 0.45 (bench/disk_shape_cases.h's hull, built
// on first use) at kPoolSize random poses against a disk of radius 0.5 at
// random poses: the same hull queried again and again, as a planner does.
// Variants distance_disk_libccd and distance_flat_cylinder_<libccd|indep>.
//
// Hull contacts: disk_hull_contacts/<N>/<disk|flat_cylinder_libccd>/double,
// fcl::collide asking for one contact (its exact penetration depth for the
// disk, libccd's EPA for the flat cylinder) on 256 intersecting poses of the
// hull of disk_convex_hulls/<N>. disk_large_hull_contacts_in_turn/<N>/<...>/double:
// the same on 1024 hulls of N random points in turn, one intersecting pose
// each (hulls a thread does not keep, as disk_large_hulls_in_turn).
//
// Hulls in turn: disk_hulls_in_turn/<H>/<variant>/double, H Convex hulls of
// 40 random points on the sphere of radius 0.45, the pool's case k against
// hull k % H: a scene's hulls queried one after another, as a broadphase
// visits them (each thread keeps the geometry of up to 1024 hulls, within
// 48 MiB). disk_large_hulls_in_turn/<N>/<variant>/double: the same with 1024
// hulls of N random points, more than a thread keeps.
//
// Run with repetitions and read the median aggregates, e.g.
//   bench_disk_shapes --benchmark_repetitions=5 --benchmark_display_aggregates_only=true
//   bench_disk_shapes --benchmark_filter='disk_shapes/box/'
#include <fcl_disk/fcl_disk.h>  // first: declares the float fcl::distance/collide instantiations
#include <fcl_disk/disk_shape_distance.h>

#include <benchmark/benchmark.h>

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "disk_shape_cases.h"

namespace {

namespace dsc = fcl_disk_shape_cases;
using dsc::ShapeKind;

constexpr std::size_t kPoolSize = 1024;  // a power of two: index = i & (kPoolSize - 1)
constexpr std::uint64_t kSeed = 20240601;
template <typename S>
constexpr S kOverlapTolerance = sizeof(S) == sizeof(float) ? S(1e-5) : S(1e-9);

template <typename S>
using Objects = std::vector<std::unique_ptr<fcl::CollisionObject<S>>>;

template <typename S>
struct Pool {
  Objects<S> disk, shape, sphere, flat_cylinder;  ///< case k in slot k of each
};

template <typename S>
const Pool<S>& pool(ShapeKind kind) {
  static std::vector<std::unique_ptr<Pool<S>>> pools(dsc::allShapeKinds().size());
  auto& slot = pools[static_cast<int>(kind)];
  if (!slot) {
    slot = std::make_unique<Pool<S>>();
    for (const dsc::CaseSpec& c : dsc::makeCases(kind, kPoolSize, kSeed)) {
      const S r = S(c.disk_radius);
      const fcl::Transform3<S> X_WD = dsc::toS<S>(c.X_WD);
      slot->disk.push_back(std::make_unique<fcl::CollisionObject<S>>(
          std::make_shared<fcl_disk::Disk<S>>(r), X_WD));
      slot->sphere.push_back(std::make_unique<fcl::CollisionObject<S>>(
          std::make_shared<fcl::Sphere<S>>(r), X_WD));
      slot->flat_cylinder.push_back(std::make_unique<fcl::CollisionObject<S>>(
          std::make_shared<fcl::Cylinder<S>>(r, S(0)), X_WD));
      slot->shape.push_back(std::make_unique<fcl::CollisionObject<S>>(
          dsc::makeShape<S>(c.shape), dsc::toS<S>(c.X_WS)));
    }
  }
  return *slot;
}

enum class Variant {
  distance_disk,
  distance_swapped,
  distance_sphere,
  distance_flat_cylinder,
  collide_disk,
  collide_sphere
};

struct Query {
  ShapeKind kind;
  Variant variant;
  fcl::GJKSolverType solver = fcl::GST_LIBCCD;
};

std::string variantName(const Query& q) {
  const char* solver = q.solver == fcl::GST_LIBCCD ? "libccd" : "indep";
  switch (q.variant) {
    case Variant::distance_disk: return std::string("distance_disk_") + solver;
    case Variant::distance_swapped: return std::string("distance_swapped_") + solver;
    case Variant::distance_sphere: return std::string("distance_sphere_") + solver;
    case Variant::distance_flat_cylinder: return std::string("distance_flat_cylinder_") + solver;
    case Variant::collide_disk: return "collide_disk";
    case Variant::collide_sphere: return "collide_sphere";
  }
  return "?";
}

/// The two objects of case k, in query order.
template <typename S>
std::pair<const fcl::CollisionObject<S>*, const fcl::CollisionObject<S>*> objects(
    const Pool<S>& p, Variant variant, std::size_t k) {
  switch (variant) {
    case Variant::distance_disk:
    case Variant::collide_disk: return {p.disk[k].get(), p.shape[k].get()};
    case Variant::distance_swapped: return {p.shape[k].get(), p.disk[k].get()};
    case Variant::distance_sphere:
    case Variant::collide_sphere: return {p.sphere[k].get(), p.shape[k].get()};
    case Variant::distance_flat_cylinder: return {p.flat_cylinder[k].get(), p.shape[k].get()};
  }
  return {nullptr, nullptr};
}

bool isCollide(Variant v) { return v == Variant::collide_disk || v == Variant::collide_sphere; }

/// One query on case k; returns whether it answered "overlap".
template <typename S>
inline bool runQuery(const Pool<S>& p, const Query& q, std::size_t k, S* distance_out) {
  const auto [o1, o2] = objects(p, q.variant, k);
  if (isCollide(q.variant)) {
    fcl::CollisionRequest<S> request;
    request.gjk_solver_type = q.solver;
    fcl::CollisionResult<S> result;
    const std::size_t contacts = fcl::collide(o1, o2, request, result);
    benchmark::DoNotOptimize(result);
    return contacts > 0;
  }
  fcl::DistanceRequest<S> request;
  request.gjk_solver_type = q.solver;
  fcl::DistanceResult<S> result;
  const S d = fcl::distance(o1, o2, request, result);
  benchmark::DoNotOptimize(result);
  if (distance_out) *distance_out = result.min_distance;
  return d <= kOverlapTolerance<S>;
}

/// The benchmark loop: query q on the pool's cases in turn, one a iteration.
template <typename S>
void cycleThroughPool(benchmark::State& state, const Pool<S>& p, const Query& q) {
  std::size_t i = 0;
  std::int64_t overlaps = 0;
  for (auto _ : state) {
    overlaps += runQuery<S>(p, q, i++ & (kPoolSize - 1), nullptr);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["pool"] = kPoolSize;
  state.counters["overlap"] =
      double(overlaps) / double(std::max<std::int64_t>(1, state.iterations()));
}

template <typename S>
void benchQuery(benchmark::State& state, Query q, std::string skip_reason) {
  if (!skip_reason.empty()) {
    state.SkipWithError(skip_reason.c_str());
    return;
  }
  cycleThroughPool<S>(state, pool<S>(q.kind), q);
}

/// diskShapeDistance on the pool's cases, the shape as its own type.
template <typename S, typename Shape>
void benchDirect(benchmark::State& state, ShapeKind kind) {
  const Pool<S>& p = pool<S>(kind);
  std::vector<const Shape*> shapes;
  for (const auto& o : p.shape)
    shapes.push_back(static_cast<const Shape*>(o->collisionGeometry().get()));
  std::size_t i = 0;
  std::int64_t overlaps = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & (kPoolSize - 1);
    const auto answer = fcl_disk::diskShapeDistance<S>(
        S(dsc::kDiskRadius), p.disk[k]->getTransform(), *shapes[k], p.shape[k]->getTransform());
    benchmark::DoNotOptimize(answer);
    overlaps += answer.distance <= kOverlapTolerance<S>;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["pool"] = kPoolSize;
  state.counters["overlap"] =
      double(overlaps) / double(std::max<std::int64_t>(1, state.iterations()));
}

template <typename S>
void registerDirect(ShapeKind kind, const char* scalar) {
  const std::string name =
      std::string("disk_shapes/") + dsc::shapeName(kind) + "/direct/" + scalar;
  void (*function)(benchmark::State&, ShapeKind) = nullptr;
  switch (kind) {
    case ShapeKind::sphere: function = benchDirect<S, fcl::Sphere<S>>; break;
    case ShapeKind::box: function = benchDirect<S, fcl::Box<S>>; break;
    case ShapeKind::capsule: function = benchDirect<S, fcl::Capsule<S>>; break;
    case ShapeKind::cylinder: function = benchDirect<S, fcl::Cylinder<S>>; break;
    case ShapeKind::cone: function = benchDirect<S, fcl::Cone<S>>; break;
    case ShapeKind::ellipsoid: function = benchDirect<S, fcl::Ellipsoid<S>>; break;
    case ShapeKind::convex8:
    case ShapeKind::convex40: function = benchDirect<S, fcl::Convex<S>>; break;
    case ShapeKind::halfspace: function = benchDirect<S, fcl::Halfspace<S>>; break;
    case ShapeKind::plane: function = benchDirect<S, fcl::Plane<S>>; break;
    case ShapeKind::triangle: function = benchDirect<S, fcl::TriangleP<S>>; break;
  }
  benchmark::RegisterBenchmark(name.c_str(), function, kind);
}

/// Every case of the pool once, in a child: "" if all answered, else the reason.
template <typename S>
std::string probe(const Query& q) {
  const Pool<S>& p = pool<S>(q.kind);  // built here, shared with the child
  const auto outcome = dsc::probeInChild(
      [&]() -> int {
        for (std::size_t k = 0; k < kPoolSize; ++k) {
          S d = S(0);
          runQuery<S>(p, q, k, &d);
          if (!isCollide(q.variant) && d == std::numeric_limits<S>::max()) return 10;
        }
        return 0;
      },
      [](int code) {
        return code == 10 ? std::string("no answer (distance left at max)")
                          : "exit code " + std::to_string(code);
      });
  return outcome.ok ? "" : "skipped: " + outcome.reason;
}

template <typename S>
void registerQuery(const Query& q, const char* scalar, int* skipped) {
  const std::string name = std::string("disk_shapes/") + dsc::shapeName(q.kind) + "/" +
                           variantName(q) + "/" + scalar;
  std::string reason = probe<S>(q);
  if (!reason.empty()) {
    ++*skipped;
    std::fprintf(stderr, "bench_disk_shapes: %s %s\n", name.c_str(), reason.c_str());
  }
  benchmark::RegisterBenchmark(name.c_str(), [q, reason](benchmark::State& st) {
    benchQuery<S>(st, q, reason);
  });
}

/// Intersecting cases a hull size of the disk_hull_contacts benchmarks.
constexpr std::size_t kContactCases = 256;

/// The hull sizes of the disk_convex_hulls benchmarks.
constexpr int kHullSizes[] = {40, 64, 100, 200, 400, 1000};

/// Where `value` is in `values` (the slot of a benchmark's lazily built cases).
template <std::size_t N>
std::size_t slotOf(const int (&values)[N], int value) {
  return std::size_t(std::find(std::begin(values), std::end(values), value) - std::begin(values));
}

/// A case of a disk at X_WD (and the flat cylinder at its pose) against `hull` at X_WS.
void addHullCase(const fcl::Transform3<double>& X_WD,
                 const std::shared_ptr<fcl::CollisionGeometry<double>>& hull,
                 const fcl::Transform3<double>& X_WS, Pool<double>* pool) {
  pool->disk.push_back(std::make_unique<fcl::CollisionObject<double>>(
      std::make_shared<fcl_disk::Disk<double>>(dsc::kDiskRadius), X_WD));
  pool->flat_cylinder.push_back(std::make_unique<fcl::CollisionObject<double>>(
      std::make_shared<fcl::Cylinder<double>>(dsc::kDiskRadius, 0.0), X_WD));
  pool->shape.push_back(std::make_unique<fcl::CollisionObject<double>>(hull, X_WS));
}

/// kPoolSize cases of a disk (and the flat cylinder at its pose) at random
/// poses against `hulls`, case k against hull k % hulls.size() at a random pose.
std::unique_ptr<Pool<double>> hullCases(
    const std::vector<std::shared_ptr<fcl::ShapeBase<double>>>& hulls,
    fcl_disk_test::Random& random) {
  auto pool = std::make_unique<Pool<double>>();
  for (std::size_t k = 0; k < kPoolSize; ++k) {
    const fcl::Transform3<double> X_WD = dsc::detail::randomPose(random);
    addHullCase(X_WD, hulls[k % hulls.size()], dsc::detail::randomPose(random), pool.get());
  }
  return pool;
}

/// kPoolSize cases against one Convex of `vertex_count` random points on a
/// sphere, built on first use.
const Pool<double>& hullPool(int vertex_count) {
  static std::vector<std::unique_ptr<Pool<double>>> pools(std::size(kHullSizes));
  auto& pool = pools[slotOf(kHullSizes, vertex_count)];
  if (!pool) {
    fcl_disk_test::Random random(kSeed + std::uint64_t(vertex_count));
    pool = hullCases({dsc::makeShape<double>(dsc::detail::sphereHull(vertex_count, random))}, random);
  }
  return *pool;
}

void benchHull(benchmark::State& state, int vertex_count, Query q) {
  cycleThroughPool<double>(state, hullPool(vertex_count), q);
}

/// The hull counts of the disk_hulls_in_turn benchmarks (hulls of 40
/// vertices), and the vertex counts of the larger hulls queried kLargeHullsInTurn
/// at a time (more than a thread keeps).
constexpr int kHullCounts[] = {1, 8, 64, 96, 128, 192, 1024};
constexpr int kLargeHullSizes[] = {100, 200};
constexpr int kLargeHullsInTurn = 1024;

/// kPoolSize cases against `hull_count` Convex hulls of `vertex_count` random
/// points on a sphere, case k against hull k % hull_count: the hulls queried in
/// turn.
std::unique_ptr<Pool<double>> inTurnCases(int hull_count, int vertex_count) {
  // 40-vertex pools are seeded by their hull count alone, the pools of
  // docs/performance.md's hulls-in-turn table.
  fcl_disk_test::Random random(kSeed + 7919 * std::uint64_t(hull_count) +
                               104729 * std::uint64_t(vertex_count == 40 ? 0 : vertex_count));
  std::vector<std::shared_ptr<fcl::ShapeBase<double>>> hulls;
  for (int h = 0; h < hull_count; ++h) {
    hulls.push_back(dsc::makeShape<double>(dsc::detail::sphereHull(vertex_count, random)));
  }
  return hullCases(hulls, random);
}

const Pool<double>& inTurnPool(int hull_count) {
  static std::vector<std::unique_ptr<Pool<double>>> pools(std::size(kHullCounts));
  auto& pool = pools[slotOf(kHullCounts, hull_count)];
  if (!pool) pool = inTurnCases(hull_count, 40);
  return *pool;
}

const Pool<double>& largeHullsInTurnPool(int vertex_count) {
  static std::vector<std::unique_ptr<Pool<double>>> pools(std::size(kLargeHullSizes));
  auto& pool = pools[slotOf(kLargeHullSizes, vertex_count)];
  if (!pool) pool = inTurnCases(kLargeHullsInTurn, vertex_count);
  return *pool;
}

/// A random pose of the disk and one of `hull`, drawn until they intersect.
void addIntersectingCase(const std::shared_ptr<fcl::CollisionGeometry<double>>& hull,
                         fcl_disk_test::Random& random, Pool<double>* cases) {
  const auto& convex = *static_cast<const fcl::Convex<double>*>(hull.get());
  while (true) {
    const fcl::Transform3<double> X_WD = dsc::detail::randomPose(random);
    const fcl::Transform3<double> X_WS = dsc::detail::randomPose(random);
    if (fcl_disk::diskShapeIntersect(double(dsc::kDiskRadius), X_WD, convex, X_WS,
                                     static_cast<fcl_disk::DiskContact<double>*>(nullptr))) {
      addHullCase(X_WD, hull, X_WS, cases);
      return;
    }
  }
}

/// kContactCases random poses of a disk and hullPool(vertex_count)'s hull
/// (the same hull) that intersect, for the contact benchmarks.
const Pool<double>& contactCases(int vertex_count) {
  static std::vector<std::unique_ptr<Pool<double>>> all(std::size(kHullSizes));
  auto& cases = all[slotOf(kHullSizes, vertex_count)];
  if (!cases) {
    const auto hull = std::const_pointer_cast<fcl::CollisionGeometry<double>>(
        hullPool(vertex_count).shape[0]->collisionGeometry());
    fcl_disk_test::Random random(kSeed + 31 * std::uint64_t(vertex_count));
    cases = std::make_unique<Pool<double>>();
    while (cases->disk.size() < kContactCases) addIntersectingCase(hull, random, cases.get());
  }
  return *cases;
}

/// One intersecting pose for each of kLargeHullsInTurn hulls of `vertex_count`
/// random points on a sphere, queried in turn: contacts on hulls a thread
/// does not keep.
const Pool<double>& largeHullContactCases(int vertex_count) {
  static std::vector<std::unique_ptr<Pool<double>>> all(std::size(kLargeHullSizes));
  auto& cases = all[slotOf(kLargeHullSizes, vertex_count)];
  if (!cases) {
    fcl_disk_test::Random random(kSeed + 613 * std::uint64_t(vertex_count));
    cases = std::make_unique<Pool<double>>();
    for (int h = 0; h < kLargeHullsInTurn; ++h) {
      const std::shared_ptr<fcl::CollisionGeometry<double>> hull =
          dsc::makeShape<double>(dsc::detail::sphereHull(vertex_count, random));
      addIntersectingCase(hull, random, cases.get());
    }
  }
  return *cases;
}

/// fcl::collide with one contact asked (its depth and normal) on the
/// intersecting cases in turn: the disk, or the flat cylinder under libccd's EPA.
void benchHullContacts(benchmark::State& state, const Pool<double>& cases, bool flat_cylinder) {
  const fcl::CollisionRequest<double> request(1, /*enable_contact=*/true);
  std::size_t i = 0;
  double depths = 0.0;
  for (auto _ : state) {
    const std::size_t k = i++ % cases.disk.size();
    fcl::CollisionResult<double> result;
    fcl::collide((flat_cylinder ? cases.flat_cylinder : cases.disk)[k].get(), cases.shape[k].get(),
                 request, result);
    if (result.numContacts() > 0) depths += result.getContact(0).penetration_depth;
    benchmark::DoNotOptimize(result);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["mean_depth"] = depths / double(std::max<std::int64_t>(1, state.iterations()));
}

/// `prefix`<n>/<variant>/double for each n of `counts`: fcl::distance of the
/// disk and of the flat cylinder (libccd), and fcl::collide of the disk,
/// through pool_of(n)'s hulls in turn.
template <std::size_t N>
void registerInTurn(const char* prefix, const int (&counts)[N],
                    const Pool<double>& (*pool_of)(int)) {
  for (const int n : counts) {
    for (const Query& q : {Query{ShapeKind::convex40, Variant::distance_disk, fcl::GST_LIBCCD},
                           Query{ShapeKind::convex40, Variant::distance_flat_cylinder, fcl::GST_LIBCCD},
                           Query{ShapeKind::convex40, Variant::collide_disk, fcl::GST_LIBCCD}}) {
      const std::string name = prefix + std::to_string(n) + "/" + variantName(q) + "/double";
      benchmark::RegisterBenchmark(name.c_str(), [n, q, pool_of](benchmark::State& st) {
        cycleThroughPool<double>(st, pool_of(n), q);
      });
    }
  }
}

void registerHulls() {
  for (const int vertex_count : kHullSizes) {
    for (const bool flat_cylinder : {false, true}) {
      const std::string name = "disk_hull_contacts/" + std::to_string(vertex_count) + "/" +
                               (flat_cylinder ? "flat_cylinder_libccd" : "disk") + "/double";
      benchmark::RegisterBenchmark(name.c_str(), [vertex_count, flat_cylinder](benchmark::State& st) {
        benchHullContacts(st, contactCases(vertex_count), flat_cylinder);
      });
    }
  }
  for (const int vertex_count : kLargeHullSizes) {
    for (const bool flat_cylinder : {false, true}) {
      const std::string name = "disk_large_hull_contacts_in_turn/" + std::to_string(vertex_count) +
                               "/" + (flat_cylinder ? "flat_cylinder_libccd" : "disk") + "/double";
      benchmark::RegisterBenchmark(name.c_str(), [vertex_count, flat_cylinder](benchmark::State& st) {
        benchHullContacts(st, largeHullContactCases(vertex_count), flat_cylinder);
      });
    }
  }
  registerInTurn("disk_hulls_in_turn/", kHullCounts, inTurnPool);
  registerInTurn("disk_large_hulls_in_turn/", kLargeHullSizes, largeHullsInTurnPool);
  for (const int vertex_count : kHullSizes) {
    for (const Query& q : {Query{ShapeKind::convex40, Variant::distance_disk, fcl::GST_LIBCCD},
                           Query{ShapeKind::convex40, Variant::distance_flat_cylinder, fcl::GST_LIBCCD},
                           Query{ShapeKind::convex40, Variant::distance_flat_cylinder, fcl::GST_INDEP}}) {
      const std::string name = "disk_convex_hulls/" + std::to_string(vertex_count) + "/" +
                               variantName(q) + "/double";
      benchmark::RegisterBenchmark(name.c_str(), [vertex_count, q](benchmark::State& st) {
        benchHull(st, vertex_count, q);
      });
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  fcl_disk::registerDiskFunctions(fcl_disk::DiskDistanceMethod::exact);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  int skipped = 0;
  for (ShapeKind kind : dsc::allShapeKinds()) {
    for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
      registerQuery<double>({kind, Variant::distance_disk, solver}, "double", &skipped);
      registerQuery<float>({kind, Variant::distance_disk, solver}, "float", &skipped);
    }
    registerDirect<double>(kind, "double");
    registerDirect<float>(kind, "float");
    registerQuery<double>({kind, Variant::distance_swapped, fcl::GST_LIBCCD}, "double", &skipped);
    for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP})
      registerQuery<double>({kind, Variant::distance_sphere, solver}, "double", &skipped);
    for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP})
      registerQuery<double>({kind, Variant::distance_flat_cylinder, solver}, "double", &skipped);
    registerQuery<double>({kind, Variant::collide_disk, fcl::GST_LIBCCD}, "double", &skipped);
    registerQuery<double>({kind, Variant::collide_sphere, fcl::GST_LIBCCD}, "double", &skipped);
  }
  registerHulls();
  if (skipped)
    std::fprintf(stderr, "bench_disk_shapes: %d variants skipped (probed in a child process)\n",
                 skipped);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
