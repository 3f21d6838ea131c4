// Broadphase scenes at scale (built with -DFCL_DISK_BUILD_BENCHMARKS=ON; results in
// docs/scenes.md). Not part of the test run.
//
// Three scenes of N disks, N = 1e2 .. 1e5, fixed seeds, each disk with a handful of
// near neighbours (counters report how many):
//   coins   a pile of coins: r = 12 mm, tilted up to 10 deg, scattered over a floor
//           (area grows with N) in a layer 2 cm high, so they overlap at random;
//   plates  racks of plates: r = 12 cm, 24 per rack at a 25 mm pitch with jitter,
//           nearly vertical (normals along x, tilted up to 8 deg), racks on a grid
//           of shelves;
//   rotors  a drone swarm: quadrotors (4 rotors of r = 12 cm, 34 cm apart) at
//           random in a volume that grows with N, tilted up to 20 deg, each rotor
//           tilted up to 3 deg more.
// Each scene in three variants with the same poses:
//   disk_tight     fcl_disk::DiskCollisionObject (Disk + diskWorldAABB's tight box);
//   disk_default   fcl::CollisionObject on a Disk (FCL's cube of half-width sqrt(2) r);
//   thin_cylinder  fcl::CollisionObject on fcl::Cylinder(r, 1e-6) (FCL's GJK/MPR;
//                  its box is FCL's cube too).
// Benchmarks (all on fcl::DynamicAABBTreeCollisionManager<double>):
//   build/<scene>/<variant>/N    create the N objects, registerObjects(), setup();
//   collide/<scene>/<variant>/N  all colliding pairs: manager.collide(&data, cb) with
//                                a callback that calls fcl::collide on every
//                                candidate and never stops (fcl::DefaultCollisionFunction
//                                stops once request.num_max_contacts = 1 contact is
//                                found, i.e. after the first colliding pair);
//   nearest/<scene>/<variant>/N  for every object, the distance to the nearest OTHER
//                                object: manager.distance(obj, &data, cb) visits obj
//                                itself too (the tree has no self test), so the
//                                callback skips o1 == o2 (fcl::DefaultDistanceFunction
//                                would return 0 for every object).
// nearest/plates/thin_cylinder stops at N = 1e4 (~22 CPU s per pass at 1e5).
// Scenes and trees are built outside the timed loops. Counters: per_object (CPU
// seconds per object), candidates (pairs handed to the narrowphase), colliding
// (pairs found), and the checks below.
// Checks, after the timed loop (SkipWithError on an unexplained difference):
//   disk_default must find exactly the pairs and nearest distances of disk_tight
//   (tight boxes must never lose a pair); thin_cylinder must find the same pairs up
//   to its thickness: it contains the disk, so it may add pairs whose disks are
//   within kCylinderHeight (+ MPR's tolerance), and MPR may miss pairs that touch
//   to within its tolerance. Such pairs are counted in thickness_mismatches.
// Run: bench_scenes --benchmark_repetitions=5 --benchmark_display_aggregates_only=true
#include <benchmark/benchmark.h>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/fcl_disk.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "test_random.h"

namespace {

using fcl_disk_test::Random;

// ---------------------------------------------------------------- constants
const int kSceneSizes[] = {100, 1000, 10000, 100000};
/// The largest N for nearest/plates/thin_cylinder (see registerAll()).
constexpr int kMaxPlatesGjkNearest = 10000;

/// The thin cylinder's height: thin enough to stand in for the disk in any
/// practical scene, thick enough for GJK/MPR to work (docs/performance.md).
constexpr double kCylinderHeight = 1e-6;
/// fcl::CollisionRequest::gjk_tolerance's default, which FCL passes to libccd's MPR
/// as mpr_tolerance: how close to touching the thin-cylinder verdict may be wrong.
constexpr double kMprTolerance = 1e-6;
/// Disk variants use the same solvers on the same pairs, possibly with the two
/// objects swapped; disk_intersection.h decides touching to ~1e-15 of the scene
/// (scenes here are metres across, coordinates up to ~40 m), exact_distance.h is
/// good to 1e-12 of it. 1e-11 m covers both with room.
constexpr double kDiskOrderBand = 1e-11;

constexpr double kDegree = M_PI / 180;

// coins: a 1-euro-sized coin; ~8 coin centres per (2 r)-radius circle of floor,
// in a 2 cm layer.
constexpr double kCoinRadius = 0.012;
constexpr double kCoinMaxTilt = 10 * kDegree;
constexpr double kCoinsPerSquareMetre = 8 / (M_PI * 4 * kCoinRadius * kCoinRadius);
constexpr double kCoinLayerHeight = 0.02;

// plates: dinner plates in dish racks.
constexpr double kPlateRadius = 0.12;
constexpr int kPlatesPerRack = 24;
constexpr double kPlatePitch = 0.025;
constexpr double kPlateMaxTilt = 8 * kDegree;
constexpr double kPlateJitter = 0.005;          // +- on each centre coordinate
constexpr double kRackPitchX = 0.7;             // rack length 24 * 25 mm + 10 cm gap
constexpr double kRackPitchY = 0.3;             // plate diameter + 6 cm
constexpr double kShelfPitchZ = 0.3;

// rotors: 10-inch propellers on a quadrotor with 34 cm between rotor centres
// (rotor disks 10 cm apart); ~0.3 m^3 of air per drone.
constexpr double kRotorRadius = 0.12;
constexpr double kRotorArm = 0.17;              // rotor centre at (+-arm, +-arm, 0)
constexpr double kDroneMaxTilt = 20 * kDegree;
constexpr double kRotorMaxTilt = 3 * kDegree;
constexpr double kAirPerDrone = 0.3;            // m^3

constexpr std::uint64_t kSeed = 20240605;

// ---------------------------------------------------------------- scenes
enum class SceneKind { coins, plates, rotors };
enum class Variant { disk_tight, disk_default, thin_cylinder };

const char* name(SceneKind scene) {
  switch (scene) {
    case SceneKind::coins: return "coins";
    case SceneKind::plates: return "plates";
    case SceneKind::rotors: return "rotors";
  }
  return "?";
}

const char* name(Variant variant) {
  switch (variant) {
    case Variant::disk_tight: return "disk_tight";
    case Variant::disk_default: return "disk_default";
    case Variant::thin_cylinder: return "thin_cylinder";
  }
  return "?";
}

struct DiskPlacement {
  double radius;
  fcl::Transform3d X_WD;
};

/// A rotation tilting local +Z by an angle uniform in [0, max_tilt] towards a
/// random horizontal direction, after a random spin about +Z.
Eigen::Matrix3d tilted(Random& random, double max_tilt) {
  const double azimuth = random.uniform(0, 2 * M_PI);
  const Eigen::Vector3d horizontal_axis(std::cos(azimuth), std::sin(azimuth), 0);
  return (Eigen::AngleAxisd(random.uniform(0, max_tilt), horizontal_axis) *
          Eigen::AngleAxisd(random.uniform(0, 2 * M_PI), Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

fcl::Transform3d pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& centre) {
  fcl::Transform3d X = fcl::Transform3d::Identity();
  X.linear() = R;
  X.translation() = centre;
  return X;
}

std::vector<DiskPlacement> makeCoins(Random& random, int n) {
  const double side = std::sqrt(n / kCoinsPerSquareMetre);
  std::vector<DiskPlacement> coins;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d centre(random.uniform(0, side), random.uniform(0, side),
                                 random.uniform(0, kCoinLayerHeight));
    coins.push_back({kCoinRadius, pose(tilted(random, kCoinMaxTilt), centre)});
  }
  return coins;
}

std::vector<DiskPlacement> makePlates(Random& random, int n) {
  const int racks = (n + kPlatesPerRack - 1) / kPlatesPerRack;
  const int racks_per_edge = int(std::ceil(std::cbrt(double(racks))));
  // Local +Z (the normal) to world +X: the plates stand upright along the rack.
  const Eigen::Matrix3d upright =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  std::vector<DiskPlacement> plates;
  for (int i = 0; i < n; ++i) {
    const int rack = i / kPlatesPerRack, slot = i % kPlatesPerRack;
    const Eigen::Vector3d rack_origin(kRackPitchX * (rack % racks_per_edge),
                                      kRackPitchY * ((rack / racks_per_edge) % racks_per_edge),
                                      kShelfPitchZ * (rack / (racks_per_edge * racks_per_edge)));
    const Eigen::Vector3d jitter(random.uniform(-kPlateJitter, kPlateJitter),
                                 random.uniform(-kPlateJitter, kPlateJitter),
                                 random.uniform(-kPlateJitter, kPlateJitter));
    const Eigen::Vector3d centre = rack_origin + Eigen::Vector3d(kPlatePitch * slot, 0, 0) + jitter;
    plates.push_back({kPlateRadius, pose(upright * tilted(random, kPlateMaxTilt), centre)});
  }
  return plates;
}

std::vector<DiskPlacement> makeRotors(Random& random, int n) {
  const int drones = (n + 3) / 4;
  const double side = std::cbrt(drones * kAirPerDrone);
  const double arms[4][2] = {{1, 1}, {1, -1}, {-1, 1}, {-1, -1}};
  std::vector<DiskPlacement> rotors;
  for (int d = 0; d < drones; ++d) {
    const Eigen::Vector3d drone_centre(random.uniform(0, side), random.uniform(0, side),
                                       random.uniform(0, side));
    const Eigen::Matrix3d drone_attitude = tilted(random, kDroneMaxTilt);
    for (int k = 0; k < 4 && int(rotors.size()) < n; ++k) {
      const Eigen::Vector3d arm(kRotorArm * arms[k][0], kRotorArm * arms[k][1], 0);
      rotors.push_back({kRotorRadius, pose(drone_attitude * tilted(random, kRotorMaxTilt),
                                           drone_centre + drone_attitude * arm)});
    }
  }
  return rotors;
}

const std::vector<DiskPlacement>& placements(SceneKind scene, int n) {
  static std::map<std::pair<SceneKind, int>, std::vector<DiskPlacement>> cache;
  auto it = cache.find({scene, n});
  if (it == cache.end()) {
    Random random(kSeed + 1000 * std::uint64_t(scene) + std::uint64_t(n));
    std::vector<DiskPlacement> made = scene == SceneKind::coins    ? makeCoins(random, n)
                                      : scene == SceneKind::plates ? makePlates(random, n)
                                                                   : makeRotors(random, n);
    it = cache.emplace(std::make_pair(scene, n), std::move(made)).first;
  }
  return it->second;
}

// ---------------------------------------------------------------- worlds
struct World {
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::vector<fcl::CollisionObjectd*> pointers;
  std::unique_ptr<fcl::DynamicAABBTreeCollisionManagerd> manager;
};

int indexOf(const fcl::CollisionObjectd* object) {
  return int(reinterpret_cast<std::intptr_t>(object->getUserData()));
}

/// Objects (one shape per radius, shared, as a planner would) and the tree.
World buildWorld(const std::vector<DiskPlacement>& scene, Variant variant) {
  World world;
  std::map<double, std::shared_ptr<fcl_disk::Diskd>> disks;
  std::map<double, std::shared_ptr<fcl::Cylinderd>> cylinders;
  world.objects.reserve(scene.size());
  for (const DiskPlacement& placement : scene) {
    const double r = placement.radius;
    std::unique_ptr<fcl::CollisionObjectd> object;
    if (variant == Variant::thin_cylinder) {
      auto& cylinder = cylinders[r];
      if (!cylinder) cylinder = std::make_shared<fcl::Cylinderd>(r, kCylinderHeight);
      object = std::make_unique<fcl::CollisionObjectd>(cylinder, placement.X_WD);
    } else {
      auto& disk = disks[r];
      if (!disk) disk = std::make_shared<fcl_disk::Diskd>(r);
      if (variant == Variant::disk_tight) {
        object = std::make_unique<fcl_disk::DiskCollisionObjectd>(disk, placement.X_WD);
      } else {
        object = std::make_unique<fcl::CollisionObjectd>(disk, placement.X_WD);
      }
    }
    object->setUserData(reinterpret_cast<void*>(std::intptr_t(world.objects.size())));
    world.pointers.push_back(object.get());
    world.objects.push_back(std::move(object));
  }
  world.manager = std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>();
  world.manager->registerObjects(world.pointers);
  world.manager->setup();
  return world;
}

/// The worlds of the (scene, variant) being measured, for every N; dropped when the
/// next benchmark is about another scene or variant, so that at most ~1.1e5 objects
/// of one kind are alive.
World& cachedWorld(SceneKind scene, Variant variant, int n) {
  static std::pair<SceneKind, Variant> current{scene, variant};
  static std::map<int, World> worlds;
  if (current != std::make_pair(scene, variant)) {
    worlds.clear();
    current = {scene, variant};
  }
  auto it = worlds.find(n);
  if (it == worlds.end()) it = worlds.emplace(n, buildWorld(placements(scene, n), variant)).first;
  return it->second;
}

// ---------------------------------------------------------------- callbacks
using Pair = std::pair<int, int>;

struct CollideData {
  long candidates = 0;
  std::vector<Pair> colliding;
};

/// Every colliding pair: fcl::collide on each candidate, never "done".
bool collectCollidingPair(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
  auto* collide_data = static_cast<CollideData*>(data);
  ++collide_data->candidates;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  if (fcl::collide(o1, o2, request, result) > 0) {
    const int i = indexOf(o1), j = indexOf(o2);
    collide_data->colliding.emplace_back(std::min(i, j), std::max(i, j));
  }
  return false;
}

struct NearestData {
  long candidates = 0;
  double nearest = std::numeric_limits<double>::max();
};

/// The nearest OTHER object: skips the query object itself. FCL's unsigned distance
/// of overlapping GJK shapes is -1; read as 0. Nothing is nearer than 0, so stop.
bool nearestOther(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data,
                  double& dist) {
  if (o1 == o2) return false;
  auto* nearest = static_cast<NearestData*>(data);
  ++nearest->candidates;
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  fcl::distance(o1, o2, request, result);
  nearest->nearest = std::min(nearest->nearest, std::max(result.min_distance, 0.0));
  dist = nearest->nearest;
  return nearest->nearest <= 0;
}

std::vector<Pair> allCollidingPairs(const World& world, long* candidates) {
  CollideData data;
  world.manager->collide(&data, collectCollidingPair);
  std::sort(data.colliding.begin(), data.colliding.end());
  if (candidates) *candidates = data.candidates;
  return data.colliding;
}

std::vector<double> allNearest(const World& world, long* candidates) {
  std::vector<double> nearest(world.pointers.size());
  long total = 0;
  for (std::size_t i = 0; i < world.pointers.size(); ++i) {
    NearestData data;
    world.manager->distance(world.pointers[i], &data, nearestOther);
    nearest[i] = data.nearest;
    total += data.candidates;
  }
  if (candidates) *candidates = total;
  return nearest;
}

/// disk_tight's answers, the reference for the checks (own world, built once).
struct Reference {
  std::vector<Pair> colliding;
  std::vector<double> nearest;
};

const Reference& reference(SceneKind scene, int n) {
  static std::map<std::pair<SceneKind, int>, Reference> cache;
  auto it = cache.find({scene, n});
  if (it == cache.end()) {
    const World world = buildWorld(placements(scene, n), Variant::disk_tight);
    it = cache.emplace(std::make_pair(scene, n),
                       Reference{allCollidingPairs(world, nullptr), allNearest(world, nullptr)})
             .first;
  }
  return it->second;
}

// ---------------------------------------------------------------- checks
struct PairCheck {
  long thickness_mismatches = 0;  ///< explained by the cylinder's thickness / MPR tolerance
  long unexplained = 0;
  std::string first_unexplained;
};

/// Compares the colliding pairs of `variant` with disk_tight's on the same poses.
PairCheck checkPairs(SceneKind scene, int n, Variant variant, const std::vector<Pair>& found) {
  const std::vector<DiskPlacement>& disks = placements(scene, n);
  const std::vector<Pair>& expected = reference(scene, n).colliding;
  std::vector<Pair> only_found, only_expected;
  std::set_difference(found.begin(), found.end(), expected.begin(), expected.end(),
                      std::back_inserter(only_found));
  std::set_difference(expected.begin(), expected.end(), found.begin(), found.end(),
                      std::back_inserter(only_expected));
  PairCheck check;
  const auto classify = [&](const Pair& pair, bool only_in_variant) {
    const DiskPlacement& a = disks[pair.first];
    const DiskPlacement& b = disks[pair.second];
    // How far the pair is from flipping: the disks' distance if apart, the
    // separating translation if they intersect.
    fcl_disk::DiskContact<double> contact;
    const bool touching = fcl_disk::intersectDisks(a.radius, a.X_WD, b.radius, b.X_WD, &contact);
    const double margin =
        touching ? contact.penetration_depth
                 : fcl_disk::exactDiskDistance(a.radius, a.X_WD, b.radius, b.X_WD).distance;
    // A thin cylinder contains its disk: it may add pairs whose disks are apart by
    // up to its height (plus MPR's tolerance), and MPR may miss pairs that touch to
    // within its tolerance. Disk variants may differ only on exact ties.
    const double band = variant != Variant::thin_cylinder ? kDiskOrderBand
                        : only_in_variant                 ? kCylinderHeight + kMprTolerance
                                                          : kMprTolerance;
    if (margin <= band) {
      ++check.thickness_mismatches;
    } else if (check.unexplained++ == 0) {
      check.first_unexplained = std::string(name(variant)) +
                                (only_in_variant ? " adds" : " misses") + " pair (" +
                                std::to_string(pair.first) + ", " + std::to_string(pair.second) +
                                "), margin " + std::to_string(margin) + " m";
    }
  };
  for (const Pair& pair : only_found) classify(pair, /*only_in_variant=*/true);
  for (const Pair& pair : only_expected) classify(pair, /*only_in_variant=*/false);
  return check;
}

void setPerObjectCounters(benchmark::State& state, int n) {
  state.SetComplexityN(n);
  state.counters["N"] = n;
  // CPU seconds per object (the rate is taken over CPU time).
  state.counters["per_object"] = benchmark::Counter(
      n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// ---------------------------------------------------------------- benchmarks
void buildBenchmark(benchmark::State& state, SceneKind scene, Variant variant) {
  const int n = int(state.range(0));
  const std::vector<DiskPlacement>& disks = placements(scene, n);
  for (auto _ : state) {
    auto world = std::make_unique<World>(buildWorld(disks, variant));
    benchmark::DoNotOptimize(world->manager.get());
    state.PauseTiming();  // freeing the world is not part of building it
    world.reset();
    state.ResumeTiming();
  }
  setPerObjectCounters(state, n);
}

void collideBenchmark(benchmark::State& state, SceneKind scene, Variant variant) {
  const int n = int(state.range(0));
  const World& world = cachedWorld(scene, variant, n);
  CollideData data;
  for (auto _ : state) {
    data.candidates = 0;
    data.colliding.clear();
    world.manager->collide(&data, collectCollidingPair);
    benchmark::ClobberMemory();
  }
  std::sort(data.colliding.begin(), data.colliding.end());
  const PairCheck check = checkPairs(scene, n, variant, data.colliding);
  if (check.unexplained > 0) {
    state.SkipWithError((std::to_string(check.unexplained) + " unexplained pair differences; " +
                         check.first_unexplained)
                            .c_str());
    return;
  }
  setPerObjectCounters(state, n);
  state.counters["candidates"] = double(data.candidates);
  state.counters["colliding"] = double(data.colliding.size());
  state.counters["candidates_per_object"] = double(data.candidates) / n;
  state.counters["thickness_mismatches"] = double(check.thickness_mismatches);
}

void nearestBenchmark(benchmark::State& state, SceneKind scene, Variant variant) {
  const int n = int(state.range(0));
  const World& world = cachedWorld(scene, variant, n);
  std::vector<double> nearest;
  long candidates = 0;
  for (auto _ : state) {
    nearest = allNearest(world, &candidates);
    benchmark::ClobberMemory();
  }
  // Disk variants: disk_tight's distances to rounding. Thin cylinders: GJK's
  // answer is d_disk - h <= d_cyl <= d_disk up to its tolerance (default request:
  // errors up to ~2e-4 of the scene, docs/performance.md); reported, not checked.
  const std::vector<double>& expected = reference(scene, n).nearest;
  double max_cylinder_deviation = 0;
  for (int i = 0; i < n; ++i) {
    const double deviation = std::abs(nearest[i] - expected[i]);
    if (variant == Variant::thin_cylinder) {
      max_cylinder_deviation = std::max(max_cylinder_deviation, deviation);
    } else if (!(deviation <= kDiskOrderBand)) {
      state.SkipWithError(("nearest distance of object " + std::to_string(i) + " is " +
                           std::to_string(nearest[i]) + ", disk_tight says " +
                           std::to_string(expected[i]))
                              .c_str());
      return;
    }
  }
  setPerObjectCounters(state, n);
  state.counters["candidates"] = double(candidates);
  state.counters["candidates_per_object"] = double(candidates) / n;
  if (variant == Variant::thin_cylinder) {
    state.counters["max_abs_diff_vs_disk"] = max_cylinder_deviation;
  }
}

void registerAll() {
  const SceneKind scenes[] = {SceneKind::coins, SceneKind::plates, SceneKind::rotors};
  const Variant variants[] = {Variant::disk_tight, Variant::disk_default, Variant::thin_cylinder};
  using Function = void (*)(benchmark::State&, SceneKind, Variant);
  const std::pair<const char*, Function> kinds[] = {
      {"build", buildBenchmark}, {"collide", collideBenchmark}, {"nearest", nearestBenchmark}};
  for (SceneKind scene : scenes) {
    for (Variant variant : variants) {
      for (const auto& [kind, function] : kinds) {
        const std::string title = std::string(kind) + "/" + name(scene) + "/" + name(variant);
        auto* benchmark = benchmark::RegisterBenchmark(title.c_str(), function, scene, variant);
        for (int n : kSceneSizes) {
          // Skipped: GJK nearest-neighbour in the plate racks costs ~220 CPU us per
          // object at N = 1e4 (~200 candidates each), so ~22 s per pass at 1e5 and,
          // on this shared machine, minutes with repetitions.
          const bool too_slow = function == nearestBenchmark && scene == SceneKind::plates &&
                                variant == Variant::thin_cylinder && n > kMaxPlatesGjkNearest;
          if (!too_slow) benchmark->Arg(n);
        }
        benchmark->Unit(benchmark::kMillisecond)->Complexity();
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  registerAll();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
