// Concurrency: plain fcl::distance / fcl::collide and per-thread broadphase
// managers, called from many threads at once, give bit for bit the answers the
// main thread computed serially beforehand. Covered: disk pairs (separated,
// intersecting, near-touching) through the CollisionObject and the
// geometry + transform APIs, float and double, both GJK solver types; pairs that
// fcl_disk forwards to FCL (real cylinders, disks against spheres and boxes);
// disks against a triangle mesh and an octree (fcl_disk's traversals, whose
// queues are per-thread scratch);
// and the same while another thread registers: the first Disk or registration
// call, the same method again and again, or switching methods (each answer is
// then one of the two methods' serial answers). FCL's tables themselves are
// patched at load time, before main() (TablesArePatchedBeforeMain).
//
// Sharing rules followed here (FCL's own; docs/robustness.md): geometries and
// CollisionObjects are built before the threads start and only read by them
// (constructing a CollisionObject writes its geometry's local AABB); requests,
// results and broadphase managers belong to one thread.
//
// Also built with ThreadSanitizer (scripts/sanitize.sh); the work per test is
// sized so that a Release run takes about a second and a TSan run well under a
// minute on two cores.
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/detail/distance_func_matrix.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/fcl_disk.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "disk_mesh_families.h"
#include "test_random.h"

namespace {

using fcl_disk::DiskDistanceMethod;
using fcl_disk_test::Random;
using Pose = fcl::Transform3<double>;

// More threads than CI's two cores, so the scheduler preempts queries midway
// and every kind of query runs next to every other kind.
constexpr int kWorkerThreads = 8;
// Each thread runs every query this many times. Sized for time, not coverage:
// about half a second per test in Release, about ten seconds under TSan (two
// shared cores).
constexpr int kRounds = 10;
// A few hundred disk pairs, a third of each kind (separated, intersecting,
// near-touching); fewer forwarded pairs, which cost a GJK run each.
constexpr int kDiskPairsPerKind = 100;
constexpr int kOtherPairs = 40;
constexpr int kBroadphaseObjects = 40;
constexpr std::size_t kMaxContacts = 4;
// Near-touching pairs: separated pairs moved together until the gap is
// +-1e-12..1e-6 (negative: just overlapping); the solvers' hardest region.
constexpr double kNearTouchingGapMin = 1e-12;
constexpr double kNearTouchingGapMax = 1e-6;
constexpr std::uint64_t kSceneSeed = 0xc0'c0'2024;
// The environments: a height field of 2 * 8^2 triangles over [-1, 1]^2, and an
// octree of a few occupied blobs (5 cm cells, within ~0.5 of its origin).
constexpr int kTerrainCells = 8;
constexpr std::uint64_t kOcTreeSeed = 7;

// ----------------------------------------------------------------------------
// What a query answered, as bits.

/// The bit patterns of everything a query returned. Equal fingerprints mean the
/// same answer bit for bit (+0 and -0 differ, as do NaN payloads), which is
/// what threads must reproduce: the solvers keep no state between calls.
class Fingerprint {
 public:
  void add(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    words_.push_back(bits);
  }
  void add(float x) {
    std::uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    words_.push_back(bits);
  }
  template <typename S>
  void add(const fcl::Vector3<S>& v) {
    for (int i = 0; i < 3; ++i) add(v[i]);
  }
  void addInteger(std::int64_t n) { words_.push_back(static_cast<std::uint64_t>(n)); }
  void addPointer(const void* p) { words_.push_back(reinterpret_cast<std::uintptr_t>(p)); }

  bool operator==(const Fingerprint& other) const { return words_ == other.words_; }
  bool operator!=(const Fingerprint& other) const { return !(*this == other); }

 private:
  std::vector<std::uint64_t> words_;
};

template <typename S>
Fingerprint fingerprintOf(S returned, const fcl::DistanceResult<S>& result) {
  Fingerprint f;
  f.add(returned);
  f.add(result.min_distance);
  f.add(result.nearest_points[0]);
  f.add(result.nearest_points[1]);
  f.addPointer(result.o1);
  f.addPointer(result.o2);
  f.addInteger(result.b1);
  f.addInteger(result.b2);
  return f;
}

template <typename S>
Fingerprint fingerprintOf(std::size_t returned, const fcl::CollisionResult<S>& result) {
  Fingerprint f;
  f.addInteger(static_cast<std::int64_t>(returned));
  f.addInteger(static_cast<std::int64_t>(result.numContacts()));
  for (std::size_t i = 0; i < result.numContacts(); ++i) {
    const fcl::Contact<S>& contact = result.getContact(i);
    f.addPointer(contact.o1);
    f.addPointer(contact.o2);
    f.addInteger(contact.b1);
    f.addInteger(contact.b2);
    f.add(contact.pos);
    f.add(contact.normal);
    f.add(contact.penetration_depth);
  }
  return f;
}

// ----------------------------------------------------------------------------
// The scene: shapes and poses in double, built once per scalar type.

struct ShapeSpec {
  enum class Type { disk, cylinder, sphere, box, convex, mesh, octree } type;
  double a = 0, b = 0, c = 0;  // disk/sphere: radius; cylinder: radius, length; box, convex
                               // (a box as a Convex, each query's own object): sides;
                               // mesh (BVHModel<OBBRSS>), octree: fixed, see kTerrainCells
};

struct PairSpec {
  std::string kind;
  ShapeSpec shape1, shape2;
  Pose X_W1, X_W2;
};

struct PlacedShape {
  ShapeSpec shape;
  Pose X_W;
};

Pose randomPose(Random& random, double spread) {
  Pose X = Pose::Identity();
  X.linear() = random.rotation();
  X.translation() = random.inBall(spread);
  return X;
}

ShapeSpec randomDisk(Random& random) {
  return {ShapeSpec::Type::disk, random.uniform(0.2, 1.0)};
}

double exactDistance(const PairSpec& pair) {
  return fcl_disk::exactDiskDistance(pair.shape1.a, pair.X_W1, pair.shape2.a, pair.X_W2).distance;
}

PairSpec separatedDiskPair(Random& random) {
  constexpr double kClearlyApart = 0.05;  // keeps this kind distinct from near-touching
  for (;;) {
    PairSpec pair{"disk-disk separated", randomDisk(random), randomDisk(random),
                  randomPose(random, 2.5), randomPose(random, 2.5)};
    if (exactDistance(pair) > kClearlyApart) return pair;
  }
}

PairSpec intersectingDiskPair(Random& random) {
  for (;;) {
    PairSpec pair{"disk-disk intersecting", randomDisk(random), randomDisk(random),
                  randomPose(random, 2.5), Pose::Identity()};
    pair.X_W2.linear() = random.rotation();
    pair.X_W2.translation() = pair.X_W1.translation() + random.inBall(0.5 * pair.shape1.a);
    if (exactDistance(pair) == 0.0) return pair;
  }
}

/// Moves disk 2 of a separated pair along the nearest direction until the gap is
/// tiny: translating a convex set along its nearest direction shrinks the
/// distance by exactly the translation.
PairSpec nearTouchingDiskPair(Random& random) {
  PairSpec pair = separatedDiskPair(random);
  pair.kind = "disk-disk near-touching";
  const auto nearest =
      fcl_disk::exactDiskDistance(pair.shape1.a, pair.X_W1, pair.shape2.a, pair.X_W2);
  const Eigen::Vector3d direction = (nearest.p_W2 - nearest.p_W1) / nearest.distance;
  const double gap = (random.chance(0.5) ? 1.0 : -1.0) *
                     random.logUniform(kNearTouchingGapMin, kNearTouchingGapMax);
  pair.X_W2.translation() -= (nearest.distance - gap) * direction;
  return pair;
}

ShapeSpec randomOtherShape(Random& random, ShapeSpec::Type type) {
  switch (type) {
    case ShapeSpec::Type::disk: return randomDisk(random);
    case ShapeSpec::Type::cylinder:
      return {type, random.uniform(0.2, 0.6), random.uniform(0.2, 1.0)};
    case ShapeSpec::Type::sphere: return {type, random.uniform(0.2, 0.6)};
    case ShapeSpec::Type::box:
    case ShapeSpec::Type::convex:
      return {type, random.uniform(0.2, 0.8), random.uniform(0.2, 0.8), random.uniform(0.2, 0.8)};
    case ShapeSpec::Type::mesh:
    case ShapeSpec::Type::octree: return {type};
  }
  return {};
}

/// Pairs other than disk-disk: with disks, the other shapes' pairs (FCL's own
/// functions for real cylinders) and fcl_disk's mesh and octree traversals;
/// without disks, pairs that reach FCL's own functions through fcl_disk's
/// wrapper (cylinder slots) or not at all, which can be queried before
/// registration.
std::vector<PairSpec> otherPairs(Random& random, bool with_disks) {
  using T = ShapeSpec::Type;
  struct Kind {
    const char* name;
    T type1, type2;
  };
  const std::vector<Kind> kinds =
      with_disks ? std::vector<Kind>{{"cylinder-cylinder", T::cylinder, T::cylinder},
                                     {"disk-sphere", T::disk, T::sphere},
                                     {"box-disk", T::box, T::disk},
                                     // fcl_disk keeps each thread's last hull: many
                                     // hulls queried in any order on any thread
                                     {"disk-convex", T::disk, T::convex},
                                     {"disk-cylinder", T::disk, T::cylinder},
                                     {"disk-mesh", T::disk, T::mesh},
                                     {"octree-disk", T::octree, T::disk}}
                 : std::vector<Kind>{{"cylinder-cylinder", T::cylinder, T::cylinder},
                                     {"sphere-cylinder", T::sphere, T::cylinder},
                                     {"cylinder-box", T::cylinder, T::box},
                                     {"sphere-box", T::sphere, T::box}};
  std::vector<PairSpec> pairs;
  for (int i = 0; i < kOtherPairs; ++i) {
    const Kind& kind = kinds[i % kinds.size()];
    const Pose X_W1 = randomPose(random, 1.0);
    Pose X_W2 = randomPose(random, 1.0);
    X_W2.translation() += X_W1.translation();
    pairs.push_back({kind.name, randomOtherShape(random, kind.type1),
                     randomOtherShape(random, kind.type2), X_W1, X_W2});
  }
  return pairs;
}

std::vector<PlacedShape> broadphaseScene(Random& random) {
  using T = ShapeSpec::Type;
  // No mesh: FCL's own sphere-mesh distance reads an uninitialised distance when
  // the two meet (docs/scenes.md), which no thread can be expected to repeat.
  constexpr T kTypes[] = {T::disk, T::disk, T::disk, T::disk, T::disk, T::box, T::sphere, T::cylinder};
  std::vector<PlacedShape> scene;
  for (int i = 0; i < kBroadphaseObjects; ++i) {
    scene.push_back({randomOtherShape(random, kTypes[i % std::size(kTypes)]), randomPose(random, 2.5)});
  }
  return scene;
}

template <typename S>
std::shared_ptr<fcl::CollisionGeometry<S>> makeGeometry(const ShapeSpec& shape) {
  switch (shape.type) {
    case ShapeSpec::Type::disk: return std::make_shared<fcl_disk::Disk<S>>(S(shape.a));
    case ShapeSpec::Type::cylinder: return std::make_shared<fcl::Cylinder<S>>(S(shape.a), S(shape.b));
    case ShapeSpec::Type::sphere: return std::make_shared<fcl::Sphere<S>>(S(shape.a));
    case ShapeSpec::Type::box:
      return std::make_shared<fcl::Box<S>>(S(shape.a), S(shape.b), S(shape.c));
    case ShapeSpec::Type::convex: {
      const S x = S(shape.a / 2), y = S(shape.b / 2), z = S(shape.c / 2);
      auto vertices = std::make_shared<std::vector<fcl::Vector3<S>>>(std::vector<fcl::Vector3<S>>{
          {-x, -y, -z}, {x, -y, -z}, {x, y, -z}, {-x, y, -z},
          {-x, -y, z},  {x, -y, z},  {x, y, z},  {-x, y, z}});
      auto faces = std::make_shared<std::vector<int>>(std::vector<int>{
          4, 0, 3, 2, 1, 4, 4, 5, 6, 7, 4, 0, 1, 5, 4, 4, 1, 2, 6, 5, 4, 2, 3, 7, 6, 4, 3, 0, 4, 7});
      return std::make_shared<fcl::Convex<S>>(vertices, 6, faces);
    }
    case ShapeSpec::Type::mesh:
      return fcl_disk_test::mesh_families::bvhOf<fcl::OBBRSS<S>>(
          fcl_disk_test::mesh_families::terrainMesh(kTerrainCells));
    case ShapeSpec::Type::octree:
      return std::make_shared<fcl::OcTree<S>>(
          fcl_disk_test::mesh_families::blobOcTree(kOcTreeSeed).build());
  }
  return nullptr;
}

template <typename S>
struct ShapePair {
  std::string kind;
  std::shared_ptr<fcl::CollisionGeometry<S>> geometry1, geometry2;
  fcl::Transform3<S> X_W1, X_W2;
  std::shared_ptr<const fcl::CollisionObject<S>> object1, object2;
};

template <typename S>
ShapePair<S> makePair(const PairSpec& spec) {
  ShapePair<S> pair{spec.kind, makeGeometry<S>(spec.shape1), makeGeometry<S>(spec.shape2),
                    spec.X_W1.cast<S>(), spec.X_W2.cast<S>(), nullptr, nullptr};
  pair.object1 = std::make_shared<fcl::CollisionObject<S>>(pair.geometry1, pair.X_W1);
  pair.object2 = std::make_shared<fcl::CollisionObject<S>>(pair.geometry2, pair.X_W2);
  return pair;
}

// ----------------------------------------------------------------------------
// Queries.

enum class Api { objects, geometries };

template <typename S>
Fingerprint distanceQuery(const ShapePair<S>& pair, Api api, fcl::GJKSolverType solver) {
  fcl::DistanceRequest<S> request(/*enable_nearest_points=*/true);
  request.gjk_solver_type = solver;
  fcl::DistanceResult<S> result;
  const S returned =
      api == Api::objects
          ? fcl::distance(pair.object1.get(), pair.object2.get(), request, result)
          : fcl::distance(pair.geometry1.get(), pair.X_W1, pair.geometry2.get(), pair.X_W2,
                          request, result);
  return fingerprintOf(returned, result);
}

template <typename S>
Fingerprint collisionQuery(const ShapePair<S>& pair, Api api, fcl::GJKSolverType solver) {
  fcl::CollisionRequest<S> request(kMaxContacts, /*enable_contact=*/true);
  request.gjk_solver_type = solver;
  fcl::CollisionResult<S> result;
  const std::size_t returned =
      api == Api::objects
          ? fcl::collide(pair.object1.get(), pair.object2.get(), request, result)
          : fcl::collide(pair.geometry1.get(), pair.X_W1, pair.geometry2.get(), pair.X_W2,
                         request, result);
  return fingerprintOf(returned, result);
}

/// One thread's broadphase managers over the shared objects (a manager keeps
/// per-query state, so it is never shared).
template <typename S>
struct Broadphase {
  explicit Broadphase(const std::vector<fcl::CollisionObject<S>*>& objects) {
    manager.registerObjects(objects);
    manager.setup();
  }
  fcl::DynamicAABBTreeCollisionManager<S> manager;
};

struct ThreadState {
  ThreadState(const std::vector<fcl::CollisionObject<double>*>& objects_d,
              const std::vector<fcl::CollisionObject<float>*>& objects_f)
      : broadphase_d(objects_d), broadphase_f(objects_f) {}
  Broadphase<double> broadphase_d;
  Broadphase<float> broadphase_f;
  fcl::DynamicAABBTreeCollisionManager<double>& manager(double) { return broadphase_d.manager; }
  fcl::DynamicAABBTreeCollisionManager<float>& manager(float) { return broadphase_f.manager; }
};

template <typename S>
Fingerprint broadphaseDistanceQuery(ThreadState& state) {
  fcl::DefaultDistanceData<S> data;
  data.request.enable_nearest_points = true;
  state.manager(S()).distance(&data, fcl::DefaultDistanceFunction<S>);
  return fingerprintOf(data.result.min_distance, data.result);
}

template <typename S>
Fingerprint broadphaseCollisionQuery(ThreadState& state) {
  fcl::DefaultCollisionData<S> data;
  data.request.num_max_contacts = kMaxContacts * kBroadphaseObjects * kBroadphaseObjects;
  data.request.enable_contact = true;
  state.manager(S()).collide(&data, fcl::DefaultCollisionFunction<S>);
  return fingerprintOf(data.result.numContacts(), data.result);
}

struct Query {
  std::string name;
  std::function<Fingerprint(ThreadState&)> run;
  /// The broadphase distance is a minimum over many pair answers; while methods
  /// are switched it may combine answers of both, so it matches neither serial run.
  bool combines_pair_distances = false;
};

/// The shared, read-only data of one test and every query over it. Queries keep
/// pointers into it, so it never moves.
class Workload {
 public:
  Workload(const std::vector<PairSpec>& pairs, const std::vector<PlacedShape>& broadphase) {
    buildScalar(pairs, broadphase, "double", pairs_d_, objects_d_, object_pointers_d_);
    buildScalar(pairs, broadphase, "float", pairs_f_, objects_f_, object_pointers_f_);
  }
  Workload(const Workload&) = delete;
  Workload& operator=(const Workload&) = delete;

  const std::vector<Query>& queries() const { return queries_; }
  ThreadState makeThreadState() const { return ThreadState(object_pointers_d_, object_pointers_f_); }

 private:
  template <typename S>
  void buildScalar(const std::vector<PairSpec>& specs, const std::vector<PlacedShape>& broadphase,
                   const std::string& scalar, std::vector<ShapePair<S>>& pairs,
                   std::vector<std::unique_ptr<fcl::CollisionObject<S>>>& objects,
                   std::vector<fcl::CollisionObject<S>*>& object_pointers) {
    pairs.reserve(specs.size());  // queries point into it
    for (const PairSpec& spec : specs) pairs.push_back(makePair<S>(spec));
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const ShapePair<S>* pair = &pairs[i];
      for (Api api : {Api::objects, Api::geometries}) {
        for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
          const std::string name = pair->kind + " #" + std::to_string(i) + " (" + scalar +
                                   (api == Api::objects ? ", objects" : ", geometries") +
                                   (solver == fcl::GST_LIBCCD ? ", libccd)" : ", indep)");
          queries_.push_back({"distance " + name, [pair, api, solver](ThreadState&) {
                                return distanceQuery(*pair, api, solver);
                              }});
          queries_.push_back({"collide " + name, [pair, api, solver](ThreadState&) {
                                return collisionQuery(*pair, api, solver);
                              }});
        }
      }
    }
    for (const PlacedShape& placed : broadphase) {
      objects.push_back(
          std::make_unique<fcl::CollisionObject<S>>(makeGeometry<S>(placed.shape), placed.X_W.cast<S>()));
      object_pointers.push_back(objects.back().get());
    }
    if (!broadphase.empty()) {
      queries_.push_back({"broadphase distance (" + scalar + ")", broadphaseDistanceQuery<S>,
                          /*combines_pair_distances=*/true});
      queries_.push_back({"broadphase collide (" + scalar + ")", broadphaseCollisionQuery<S>});
    }
  }

  std::vector<ShapePair<double>> pairs_d_;
  std::vector<ShapePair<float>> pairs_f_;
  std::vector<std::unique_ptr<fcl::CollisionObject<double>>> objects_d_;
  std::vector<std::unique_ptr<fcl::CollisionObject<float>>> objects_f_;
  std::vector<fcl::CollisionObject<double>*> object_pointers_d_;
  std::vector<fcl::CollisionObject<float>*> object_pointers_f_;
  std::vector<Query> queries_;
};

/// Disk pairs of every kind, forwarded pairs and a broadphase scene.
std::unique_ptr<Workload> fullWorkload() {
  Random random(kSceneSeed);
  std::vector<PairSpec> pairs;
  for (int i = 0; i < kDiskPairsPerKind; ++i) {
    pairs.push_back(separatedDiskPair(random));
    pairs.push_back(intersectingDiskPair(random));
    pairs.push_back(nearTouchingDiskPair(random));
  }
  for (PairSpec& pair : otherPairs(random, /*with_disks=*/true)) pairs.push_back(pair);
  return std::make_unique<Workload>(pairs, broadphaseScene(random));
}

std::vector<Fingerprint> serialAnswers(const Workload& workload) {
  ThreadState state = workload.makeThreadState();
  std::vector<Fingerprint> answers;
  for (const Query& query : workload.queries()) answers.push_back(query.run(state));
  return answers;
}

// ----------------------------------------------------------------------------
// Running the queries from many threads.

/// What one thread saw; merged after the threads end.
struct Tally {
  long queries = 0;
  long mismatches = 0;
  // While methods are switched: answers that only one method's serial run gave.
  long serial_only_answers = 0;
  long alternative_only_answers = 0;
  std::string first_mismatch;

  void merge(const Tally& other) {
    queries += other.queries;
    mismatches += other.mismatches;
    serial_only_answers += other.serial_only_answers;
    alternative_only_answers += other.alternative_only_answers;
    if (first_mismatch.empty()) first_mismatch = other.first_mismatch;
  }
};

struct AcceptedAnswers {
  const std::vector<Fingerprint>* serial;
  /// While methods are switched: the other method's serial answers; else null.
  const std::vector<Fingerprint>* alternative = nullptr;
};

/// Runs every query once, starting at `start` so that threads run different
/// kinds of queries at the same moment.
void checkOneRound(const Workload& workload, const AcceptedAnswers& accepted, std::size_t start,
                   ThreadState& state, Tally& tally) {
  const std::vector<Query>& queries = workload.queries();
  for (std::size_t k = 0; k < queries.size(); ++k) {
    const std::size_t i = (start + k) % queries.size();
    const Query& query = queries[i];
    if (accepted.alternative && query.combines_pair_distances) continue;
    const Fingerprint answer = query.run(state);
    ++tally.queries;
    const bool methods_differ =
        accepted.alternative && (*accepted.serial)[i] != (*accepted.alternative)[i];
    if (answer == (*accepted.serial)[i]) {
      if (methods_differ) ++tally.serial_only_answers;
      continue;
    }
    if (methods_differ && answer == (*accepted.alternative)[i]) {
      ++tally.alternative_only_answers;
      continue;
    }
    ++tally.mismatches;
    if (tally.first_mismatch.empty()) tally.first_mismatch = query.name;
  }
}

/// Starts kWorkerThreads workers that each run `rounds` rounds of every query,
/// and optionally one more thread running `meanwhile(stop)` until they finish.
Tally queryFromManyThreads(const Workload& workload, const AcceptedAnswers& accepted, int rounds,
                           const std::function<void(const std::atomic<bool>& stop)>& meanwhile = {}) {
  std::atomic<bool> stop{false};
  std::thread other;
  if (meanwhile) other = std::thread([&] { meanwhile(stop); });
  std::mutex tally_mutex;
  Tally total;
  std::vector<std::thread> workers;
  for (int t = 0; t < kWorkerThreads; ++t) {
    workers.emplace_back([&, t] {
      ThreadState state = workload.makeThreadState();
      Tally tally;
      const std::size_t start = t * workload.queries().size() / kWorkerThreads;
      for (int round = 0; round < rounds; ++round) {
        checkOneRound(workload, accepted, start, state, tally);
      }
      std::lock_guard<std::mutex> lock(tally_mutex);
      total.merge(tally);
    });
  }
  for (std::thread& worker : workers) worker.join();
  stop = true;
  if (other.joinable()) other.join();
  return total;
}

// ----------------------------------------------------------------------------
// Tests.

/// Whether the live table's cylinder slots no longer hold the functions FCL's
/// constructor puts there (fcl/narrowphase/detail/distance_func_matrix-inl.h).
/// The comparison means something only if an entry fcl_disk does not patch
/// still equals FCL's function (same instantiation, same address): checked first.
/// Naming FCL's functions instantiates three of them, where building a whole
/// pristine matrix would instantiate FCL's entire float dispatch in this file.
template <typename Solver>
bool cylinderSlotsPatched() {
  using S = typename Solver::S;
  using fcl::detail::ShapeShapeDistance;
  const auto& live = fcl::getDistanceFunctionLookTable<Solver>().distance_matrix;
  EXPECT_EQ(live[fcl::GEOM_SPHERE][fcl::GEOM_BOX],
            (&ShapeShapeDistance<fcl::Sphere<S>, fcl::Box<S>, Solver>))
      << "the live table's unpatched entries are not FCL's functions: cannot tell patched slots";
  return live[fcl::GEOM_CYLINDER][fcl::GEOM_CYLINDER] !=
             &ShapeShapeDistance<fcl::Cylinder<S>, fcl::Cylinder<S>, Solver> &&
         live[fcl::GEOM_CYLINDER][fcl::GEOM_SPHERE] !=
             &ShapeShapeDistance<fcl::Cylinder<S>, fcl::Sphere<S>, Solver> &&
         live[fcl::GEOM_SPHERE][fcl::GEOM_CYLINDER] !=
             &ShapeShapeDistance<fcl::Sphere<S>, fcl::Cylinder<S>, Solver>;
}

// FCL reads its tables without synchronisation, so they must never be patched
// while another thread dispatches: fcl_disk installs when the library is loaded,
// before main() and so before any thread exists. Checked first thing in the
// process (ctest runs each test in its own process), before any Disk or
// registerDiskFunctions() call.
TEST(Concurrency, TablesArePatchedBeforeMain) {
  EXPECT_TRUE(cylinderSlotsPatched<fcl::detail::GJKSolver_libccd<float>>());
  EXPECT_TRUE(cylinderSlotsPatched<fcl::detail::GJKSolver_indep<float>>());
  EXPECT_TRUE(cylinderSlotsPatched<fcl::detail::GJKSolver_libccd<double>>());
  EXPECT_TRUE(cylinderSlotsPatched<fcl::detail::GJKSolver_indep<double>>());
}

// Registering (explicitly, or by building the first Disk) while other threads
// dispatch other shapes (real cylinders, spheres, boxes) changes none of their
// answers, during or after, and disk pairs get fcl_disk's answer afterwards.
TEST(Concurrency, RegistrationWhileOtherShapesAreQueried) {
  Random random(kSceneSeed);
  const Workload workload(otherPairs(random, /*with_disks=*/false), /*broadphase=*/{});
  const std::vector<Fingerprint> serial = serialAnswers(workload);

  constexpr int kRegisteringThreads = 3;  // racing each other into call_once
  std::atomic<int> workers_started{0};
  std::atomic<bool> registered{false};
  std::atomic<int> registering_threads_done{0};
  std::mutex tally_mutex;
  Tally total;
  std::vector<std::thread> threads;
  for (int t = 0; t < kWorkerThreads; ++t) {
    threads.emplace_back([&, t] {
      ThreadState state = workload.makeThreadState();
      Tally tally;
      const std::size_t start = t * workload.queries().size() / kWorkerThreads;
      checkOneRound(workload, {&serial}, start, state, tally);
      ++workers_started;
      while (!registered) checkOneRound(workload, {&serial}, start, state, tally);
      for (int round = 0; round < kRounds; ++round) {
        checkOneRound(workload, {&serial}, start, state, tally);
      }
      std::lock_guard<std::mutex> lock(tally_mutex);
      total.merge(tally);
    });
  }
  for (int t = 0; t < kRegisteringThreads; ++t) {
    threads.emplace_back([&, t] {
      while (workers_started < kWorkerThreads) std::this_thread::yield();
      // Both ways in: explicit registration, and a Disk's constructor.
      if (t == 0) {
        const fcl_disk::Diskf disk(1.0f);
      } else {
        fcl_disk::registerDiskFunctions(DiskDistanceMethod::exact);
      }
      if (++registering_threads_done == kRegisteringThreads) registered = true;
    });
  }
  for (std::thread& thread : threads) thread.join();

  EXPECT_EQ(total.mismatches, 0) << "first: " << total.first_mismatch;
  EXPECT_GT(total.queries, 0);
  // The hook is in: a disk pair gets fcl_disk's answer.
  auto disk = std::make_shared<fcl_disk::Diskd>(1.0);
  Pose lifted = Pose::Identity();
  lifted.translation() << 0.3, 0.0, 0.5;
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  EXPECT_EQ(fcl::distance(disk.get(), Pose::Identity(), disk.get(), lifted, request, result),
            fcl_disk::exactDiskDistance(1.0, Pose::Identity(), 1.0, lifted).distance);
}

TEST(Concurrency, QueriesFromManyThreadsMatchSerialAnswers) {
  fcl_disk::registerDiskFunctions(DiskDistanceMethod::exact);
  const auto workload = fullWorkload();
  const std::vector<Fingerprint> serial = serialAnswers(*workload);
  const Tally tally = queryFromManyThreads(*workload, {&serial}, kRounds);
  EXPECT_EQ(tally.mismatches, 0) << "first: " << tally.first_mismatch;
  EXPECT_EQ(tally.queries, long(kWorkerThreads) * kRounds * long(serial.size()));
}

// registerDiskFunctions() after installation only stores the method; storing
// the same one again and again changes no answer.
TEST(Concurrency, RegisteringTheSameMethodWhileQueryingChangesNoAnswer) {
  fcl_disk::registerDiskFunctions(DiskDistanceMethod::exact);
  const auto workload = fullWorkload();
  const std::vector<Fingerprint> serial = serialAnswers(*workload);
  long registrations = 0;
  const Tally tally =
      queryFromManyThreads(*workload, {&serial}, kRounds, [&](const std::atomic<bool>& stop) {
        while (!stop) {
          fcl_disk::registerDiskFunctions(DiskDistanceMethod::exact);
          ++registrations;
        }
      });
  EXPECT_EQ(tally.mismatches, 0) << "first: " << tally.first_mismatch;
  EXPECT_GT(registrations, 0);
}

// Switching methods while querying: every answer is one method's serial answer
// (a query reads the method once), never a blend or a GJK answer.
TEST(Concurrency, SwitchingMethodsWhileQueryingGivesOneMethodsAnswer) {
  const auto workload = fullWorkload();
  fcl_disk::registerDiskFunctions(DiskDistanceMethod::almohamad_selim);
  const std::vector<Fingerprint> serial_almohamad_selim = serialAnswers(*workload);
  fcl_disk::registerDiskFunctions(DiskDistanceMethod::exact);
  const std::vector<Fingerprint> serial_exact = serialAnswers(*workload);

  long switches = 0;
  const Tally tally = queryFromManyThreads(
      *workload, {&serial_exact, &serial_almohamad_selim}, kRounds,
      [&](const std::atomic<bool>& stop) {
        while (!stop) {
          fcl_disk::registerDiskFunctions(DiskDistanceMethod::almohamad_selim);
          fcl_disk::registerDiskFunctions(DiskDistanceMethod::exact);
          ++switches;
        }
      });
  fcl_disk::registerDiskFunctions(DiskDistanceMethod::exact);
  EXPECT_EQ(tally.mismatches, 0) << "first: " << tally.first_mismatch;
  EXPECT_GT(switches, 0);
  // Both methods answered while the threads ran: the switches took effect.
  EXPECT_GT(tally.serial_only_answers, 0);
  EXPECT_GT(tally.alternative_only_answers, 0);
}

}  // namespace
