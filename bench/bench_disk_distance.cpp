// Google Benchmark suite for fcl_disk's disk-disk solvers (built with
// -DFCL_DISK_BUILD_BENCHMARKS=ON; not part of the test run).
//
// Every benchmark cycles through the same fixed pool of kPoolSize random pairs
// (test/disk_families.h, family "random", fixed seed), one pair per iteration,
// so the branch predictor cannot learn a single case. Names:
//   direct/<solver>/<float|double>        the solver called directly;
//   fcl_distance/<solver>/<float|double>  the same through fcl::distance on Disk
//                                         CollisionObjects (method switched with
//                                         registerDiskFunctions): minus direct =
//                                         the hook's dispatch overhead;
//   fcl_distance/dispatch_only/<float|double>
//                                         the same pairs with a result already at
//                                         distance 0: the entry path and its Disk
//                                         test, no solver (the floor of the
//                                         overhead; fcl_disk's object-level
//                                         entry, docs/fcl_hook.md);
//   fcl_collide/disk/<float|double>       intersectDisks through fcl::collide;
//   fcl_distance/gjk_<libccd|indep>_cylinder_h<h>/double
//                                         FCL's GJK on Cylinder(r, h), default
//                                         request (distance_tolerance 1e-6);
//   fcl_distance/sphere_sphere/double     FCL's own closed-form sphere-sphere
//                                         entry: about what FCL's dispatch costs;
//   fcl_manager_distance/default_callback/<N>/double
//                                         a DynamicAABBTree of N disks (radius
//                                         0.3, random poses in a cube of side
//                                         2 N^(1/3)), each iteration the nearest
//                                         of them to one of N other disks through
//                                         FCL's DefaultDistanceFunction, whose
//                                         one result the candidate pairs share;
//   overhead/typeid_x2                    the tables' "is it a Disk?" test on both
//                                         geometries (typeid; the object-level
//                                         entry compares type_info addresses).
// Run with repetitions and read the median aggregates, e.g.
//   bench_disk_distance --benchmark_repetitions=10
//     --benchmark_display_aggregates_only=true
#include <benchmark/benchmark.h>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/fcl_disk.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <typeinfo>
#include <vector>

#include "disk_families.h"

namespace {

namespace fam = fcl_disk_families;

constexpr std::size_t kPoolSize = 512;  // a power of two: index = i & (kPoolSize - 1)
constexpr std::uint64_t kSeed = 20240601;
const double kHeights[] = {1e-2, 1e-4, 1e-6};
const char* const kHeightNames[] = {"1e-2", "1e-4", "1e-6"};

template <typename S>
using Objects = std::vector<std::unique_ptr<fcl::CollisionObject<S>>>;

template <typename S>
struct Pool {
  std::vector<fam::DiskPairCase<S>> cases;
  Objects<S> disk1, disk2;
  Objects<S> cyl1[3], cyl2[3];
  Objects<S> sphere1, sphere2;
};

template <typename S>
const Pool<S>& pool() {
  static const Pool<S> instance = [] {
    Pool<S> p;
    p.cases = fam::makeFamily<S>(fam::Family::random, kPoolSize, kSeed);
    for (const auto& c : p.cases) {
      p.disk1.push_back(std::make_unique<fcl::CollisionObject<S>>(
          std::make_shared<fcl_disk::Disk<S>>(c.r1), c.X_W1));
      p.disk2.push_back(std::make_unique<fcl::CollisionObject<S>>(
          std::make_shared<fcl_disk::Disk<S>>(c.r2), c.X_W2));
      for (int h = 0; h < 3; ++h) {
        p.cyl1[h].push_back(std::make_unique<fcl::CollisionObject<S>>(
            std::make_shared<fcl::Cylinder<S>>(c.r1, S(kHeights[h])), c.X_W1));
        p.cyl2[h].push_back(std::make_unique<fcl::CollisionObject<S>>(
            std::make_shared<fcl::Cylinder<S>>(c.r2, S(kHeights[h])), c.X_W2));
      }
      p.sphere1.push_back(std::make_unique<fcl::CollisionObject<S>>(
          std::make_shared<fcl::Sphere<S>>(c.r1), c.X_W1));
      p.sphere2.push_back(std::make_unique<fcl::CollisionObject<S>>(
          std::make_shared<fcl::Sphere<S>>(c.r2), c.X_W2));
    }
    return p;
  }();
  return instance;
}

void finish(benchmark::State& state) {
  state.SetItemsProcessed(state.iterations());
  state.counters["pool"] = kPoolSize;
}

// ---- the solvers alone ----------------------------------------------------

template <typename S>
void directExact(benchmark::State& state) {
  const auto& cases = pool<S>().cases;
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& c = cases[i++ & (kPoolSize - 1)];
    benchmark::DoNotOptimize(fcl_disk::exactDiskDistance(c.r1, c.X_W1, c.r2, c.X_W2));
  }
  finish(state);
}

template <typename S>
void directAlmohamadSelim(benchmark::State& state) {
  const auto& cases = pool<S>().cases;
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& c = cases[i++ & (kPoolSize - 1)];
    benchmark::DoNotOptimize(fcl_disk::almohamadSelimDiskDistance(c.r1, c.X_W1, c.r2, c.X_W2));
  }
  finish(state);
}

template <typename S>
void directIntersect(benchmark::State& state) {
  const auto& cases = pool<S>().cases;
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& c = cases[i++ & (kPoolSize - 1)];
    fcl_disk::DiskContact<S> contact;
    benchmark::DoNotOptimize(fcl_disk::intersectDisks(c.r1, c.X_W1, c.r2, c.X_W2, &contact));
    benchmark::DoNotOptimize(contact);
  }
  finish(state);
}

// ---- through FCL's dispatch -------------------------------------------------

/// One fcl::distance per iteration on the pool's pairs (objects1[k], objects2[k]),
/// with a fresh request and result each time, set up by prepare(request, result).
template <typename S, typename Prepare>
void cycleFclDistance(benchmark::State& state, const Objects<S>& objects1,
                      const Objects<S>& objects2, Prepare prepare) {
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & (kPoolSize - 1);
    fcl::DistanceRequest<S> request;
    fcl::DistanceResult<S> result;
    prepare(request, result);
    benchmark::DoNotOptimize(
        fcl::distance(objects1[k].get(), objects2[k].get(), request, result));
    benchmark::DoNotOptimize(result);
  }
  finish(state);
}

template <typename S>
void fclDistanceDisk(benchmark::State& state, fcl_disk::DiskDistanceMethod method) {
  const auto& p = pool<S>();
  fcl_disk::registerDiskFunctions(method);
  cycleFclDistance<S>(state, p.disk1, p.disk2, [](auto&, auto&) {});
  fcl_disk::registerDiskFunctions(fcl_disk::DiskDistanceMethod::exact);
}

// The dispatch alone: the same disk pairs through fcl::distance with a result
// already at distance 0, which FCL's shape-pair entries (and fcl_disk's) leave
// alone without computing anything. What remains is the entry path and its
// Disk test: the floor under any disk query through fcl::distance. This program
// links fcl_disk first, so that is fcl_disk's object-level entry with its
// shortcut (docs/fcl_hook.md); FCL's own entry (solver object, table lookup,
// virtual type queries, the slot's Disk test) runs where libfcl is linked first.
template <typename S>
void fclDistanceDispatchOnly(benchmark::State& state) {
  const auto& p = pool<S>();
  cycleFclDistance<S>(state, p.disk1, p.disk2,
                      [](auto&, fcl::DistanceResult<S>& result) { result.min_distance = S(0); });
}

template <typename S>
void fclDistanceGjkCylinder(benchmark::State& state, fcl::GJKSolverType solver, int height) {
  const auto& p = pool<S>();
  cycleFclDistance<S>(state, p.cyl1[height], p.cyl2[height],
                      [solver](fcl::DistanceRequest<S>& request, auto&) {
                        request.gjk_solver_type = solver;
                      });
}

template <typename S>
void fclDistanceSphereSphere(benchmark::State& state) {
  const auto& p = pool<S>();
  cycleFclDistance<S>(state, p.sphere1, p.sphere2, [](auto&, auto&) {});
}

template <typename S>
void fclCollideDisk(benchmark::State& state) {
  const auto& p = pool<S>();
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & (kPoolSize - 1);
    fcl::CollisionRequest<S> request;
    fcl::CollisionResult<S> result;
    benchmark::DoNotOptimize(fcl::collide(p.disk1[k].get(), p.disk2[k].get(), request, result));
    benchmark::DoNotOptimize(result);
  }
  finish(state);
}

/// A manager's nearest-disk query with FCL's default callback: the candidate
/// pairs accumulate into one DistanceResult, so those proven no nearer than it
/// holds are not solved (src/fcl_hook.cpp, diskPairNoNearerThan).
void fclManagerDistance(benchmark::State& state) {
  const int n = int(state.range(0));
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const double half_side = std::cbrt(double(n));
  const auto random_pose = [&] {
    fcl::Transform3d X = fcl::Transform3d::Identity();
    X.linear() = Eigen::Quaterniond(uniform(rng), uniform(rng), uniform(rng), uniform(rng))
                     .normalized()
                     .toRotationMatrix();
    X.translation() = half_side * Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng));
    return X;
  };
  const auto disk = std::make_shared<fcl_disk::Diskd>(0.3);
  Objects<double> in_manager, queries;
  fcl::DynamicAABBTreeCollisionManagerd manager;
  for (int i = 0; i < n; ++i) {
    in_manager.push_back(std::make_unique<fcl::CollisionObjectd>(disk, random_pose()));
    manager.registerObject(in_manager.back().get());
    queries.push_back(std::make_unique<fcl::CollisionObjectd>(disk, random_pose()));
  }
  manager.setup();
  std::size_t i = 0;
  for (auto _ : state) {
    fcl::DefaultDistanceData<double> data;
    manager.distance(queries[i++ % queries.size()].get(), &data, fcl::DefaultDistanceFunction);
    benchmark::DoNotOptimize(data.result.min_distance);
  }
  state.SetItemsProcessed(state.iterations());
}

// ---- pieces of the hook's overhead ------------------------------------------
// The tables' wrapper tells a Disk from a real Cylinder by lz == 0 and then an
// exact typeid comparison on both geometries (Disk is final); this times that
// test alone.

template <typename S>
void overheadTypeid(benchmark::State& state) {
  const auto& p = pool<S>();
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & (kPoolSize - 1);
    const fcl::CollisionGeometry<S>* g1 = p.disk1[k]->collisionGeometry().get();
    const fcl::CollisionGeometry<S>* g2 = p.disk2[k]->collisionGeometry().get();
    benchmark::DoNotOptimize(g1);
    benchmark::DoNotOptimize(g2);
    benchmark::DoNotOptimize(typeid(*g1) == typeid(fcl_disk::Disk<S>));
    benchmark::DoNotOptimize(typeid(*g2) == typeid(fcl_disk::Disk<S>));
  }
  finish(state);
}

template <typename S>
void registerScalar(const std::string& scalar) {
  using M = fcl_disk::DiskDistanceMethod;
  benchmark::RegisterBenchmark(("direct/exact/" + scalar).c_str(), directExact<S>);
  benchmark::RegisterBenchmark(("direct/almohamad_selim/" + scalar).c_str(),
                               directAlmohamadSelim<S>);
  benchmark::RegisterBenchmark(("direct/intersect/" + scalar).c_str(), directIntersect<S>);
  benchmark::RegisterBenchmark(("fcl_distance/exact/" + scalar).c_str(),
                               [](benchmark::State& st) { fclDistanceDisk<S>(st, M::exact); });
  benchmark::RegisterBenchmark(
      ("fcl_distance/almohamad_selim/" + scalar).c_str(),
      [](benchmark::State& st) { fclDistanceDisk<S>(st, M::almohamad_selim); });
  benchmark::RegisterBenchmark(("fcl_distance/dispatch_only/" + scalar).c_str(),
                               fclDistanceDispatchOnly<S>);
  benchmark::RegisterBenchmark(("fcl_collide/disk/" + scalar).c_str(), fclCollideDisk<S>);
}

}  // namespace

int main(int argc, char** argv) {
  // Install the hook (and its self-test) before any timing.
  fcl_disk::registerDiskFunctions(fcl_disk::DiskDistanceMethod::exact);
  registerScalar<float>("float");
  registerScalar<double>("double");
  benchmark::RegisterBenchmark("fcl_manager_distance/default_callback", fclManagerDistance)
      ->Arg(1000)
      ->Arg(10000);
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    for (int h : {2, 1, 0}) {  // h = 1e-6 first: the variant the targets name
      const std::string name = std::string("fcl_distance/gjk_") +
                               (solver == fcl::GST_LIBCCD ? "libccd" : "indep") +
                               "_cylinder_h" + kHeightNames[h] + "/double";
      benchmark::RegisterBenchmark(name.c_str(), [solver, h](benchmark::State& st) {
        fclDistanceGjkCylinder<double>(st, solver, h);
      });
    }
  }
  benchmark::RegisterBenchmark("fcl_distance/sphere_sphere/double",
                               fclDistanceSphereSphere<double>);
  benchmark::RegisterBenchmark("overhead/typeid_x2/double", overheadTypeid<double>);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
