// A Disk flying through an environment: a triangle mesh (fcl::BVHModel) and an
// octomap (fcl::OcTree), through plain fcl::distance / fcl::collide (built with
// -DFCL_DISK_BUILD_BENCHMARKS=ON; results in docs/scenes.md, "Disks in an environment").
// Not part of the test run.
//
// Environments (fixed seeds, generated here, built once outside the timed loops;
// both at the identity pose):
//   mesh    a terrain heightfield 2 m x 2 m (120 x 120 cells, 28,800 triangles) with
//           five crates (boxes, 12 triangles each) and four pillars (cylinders of
//           radius 6 cm, 1.2 m high, 32 sides) from fcl::generateBVHModel: 30,140
//           triangles as ONE BVHModel, timed as BVHModel<OBBRSS>, <RSS>, <OBB> and
//           <AABB>. FCL collides a shape with an AABB mesh on a COPY of the whole
//           model per query (fcl::detail::BVHShapeCollider's generic version), so
//           its collide/mesh_aabb measures that copy more than the traversal.
//           Debian's libfcl 0.7 has no distance between Sphere or Cylinder and an
//           OBB or AABB mesh (it prints "not supported", min_distance stays at
//           max()): those runs end with "no answer", untimed.
//   octree  an octomap::OcTree at 5 cm resolution, wrapped as fcl::OcTree<double>:
//           a room 2.4 m x 2.4 m inside (floor and walls 10 cm thick, walls 1.5 m
//           high) with five crates and four round columns (radius 8 cm, 1 m
//           high), voxelised at the cell centres, then pruned as octomap does
//           (equal siblings merge into larger leaves).
// Both environments share one layout: pillars/columns placed for a slalom, crates
// on a circle and one in the middle.
//
// The moving disk: r = 12 cm (a rotor), along four planner-style paths of 200
// poses, each pose a yaw along the path, a pitch and a bank (tilts 5-25 deg):
//   skim      a circle of radius 0.85 m, 1-10 cm (varying along the path) above the
//             highest ground or crate top under the disk, its lowest rim point
//             counted: over four crates, and past a pillar;
//   slalom    a weave at 0.45 m height past the four pillars, aimed 1.5-8 cm from
//             their sides (octree: columns moved onto the grid, towards the path),
//             banking up to 25 deg in the turns;
//   crossing  a descending straight-line edge (a planner's infeasible edge) through
//             the middle crate and into the ground: in contact for part of the way;
//   open      a circle 0.4 m above the pillars' tops: far from everything;
//   all       the four paths back to back (800 poses): the whole flight.
// Variants, on the same poses (one CollisionObject per pose, built outside the
// timing; a fresh request and result per query):
//   disk       fcl_disk::Disk(r): whatever answers a Disk in this build;
//   sphere     fcl::Sphere(r): FCL's own, the cheapest shape it has;
//   cylinder   fcl::Cylinder(r, 0): a real, flat FCL cylinder, which fcl_disk leaves to
//              FCL: GJK (libccd) on the flat cylinder, what FCL alone does for a disk.
// Queries: distance (default DistanceRequest) and collide (default CollisionRequest,
// num_max_contacts = 1), the moving shape as o1.
// Names: <query>/<scene>/<path>/<variant>, scene one of mesh_obbrss, mesh_rss,
// mesh_obb, mesh_aabb, octree.
//
// Timing: one benchmark iteration is one sweep of the path (Google Benchmark's
// time). Each query is also timed alone (steady_clock around the call; wall time),
// its time per pose the median over the sweeps; counters median_ns and p99_ns are
// the median and 99th percentile of those over the path's poses, per_query the sweep's
// CPU time over its poses (s). contact: the fraction of poses in contact (collide
// true, distance <= 0).
//
// Checks, after the timed loop, on every kCheckStride-th pose: a brute-force
// reference over every triangle (fcl_disk::diskShapeDistance against
// fcl::TriangleP, mesh at the identity) or every occupied leaf cell
// (fcl_disk::diskShapeDistance against fcl::Box(cell size) at the cell centre):
//   disk      distance within kCheckTolerance * scale of the reference, with scale =
//             r + R_E + |c_D| (R_E the environment's bounding radius about its
//             origin, as diskShapeDistance defines scale); collide: the verdict of
//             the reference (any triangle / cell intersecting, diskShapeIntersect)
//             unless the pose is within kCheckTolerance * scale of touching.
//             A failure is a SkipWithError (no timing reported) unless the bench
//             runs with --keep_failed_timings, which reports the timings and
//             check_failures as a counter instead.
//   cylinder  reported, not checked: max_abs_diff_vs_exact (m; FCL's -1 for
//             overlapping GJK shapes read as 0) and verdict_mismatches.
//   sphere    not checked (another shape).
// Counters from the reference, for every variant: exact_contact (fraction of the
// checked poses in contact), exact_min_mm and exact_median_mm (the disk's exact
// clearance on the checked poses: what the paths actually are).
//
// Instruction counts: `bench_environment --calls QUERY/SCENE` (e.g. distance/mesh_obbrss)
// runs the disk's queries on the whole flight (800 poses) kCallPasses times, with no
// timing and no check, and prints the sum of the answers. Under callgrind, the inclusive
// count of the query's entry (e.g. fcl_disk's mesh distance) over kCallPasses * 800 is
// its instructions per query; the environment is built before, once.
//
// Run: bench_environment --benchmark_repetitions=5 --benchmark_display_aggregates_only=true
//          --benchmark_out=environment.json --benchmark_out_format=json
//      python3 bench/environment_plot.py environment.json docs/environment.png
#include <fcl_disk/fcl_disk.h>
#include <fcl_disk/disk_shape_distance.h>

#include <benchmark/benchmark.h>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/geometric_shape_to_BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>

#include <octomap/OcTree.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "test_random.h"

namespace {

using fcl_disk_test::Random;
using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------- constants
constexpr double kDegree = M_PI / 180;
constexpr std::uint64_t kSeed = 20240612;

constexpr double kDiskRadius = 0.12;   ///< a 10-inch rotor
constexpr int kPosesPerPath = 200;
constexpr int kCheckStride = 2;        ///< brute-force check on every 2nd pose
constexpr double kCheckTolerance = 1e-12;
constexpr int kCallPasses = 5;         ///< sweeps of the flight in --calls

// mesh: terrain over [-1, 1]^2.
constexpr double kTerrainHalfSide = 1.0;
constexpr int kTerrainCells = 120;     ///< per side: 2 * 120^2 = 28,800 triangles
constexpr double kMeshPillarRadius = 0.06;
constexpr double kMeshPillarBottom = -0.2, kMeshPillarTop = 1.0;
constexpr unsigned kMeshPillarSides = 32, kMeshPillarStacks = 4;

// octree: a room over [-1.3, 1.3]^2 (walls 10 cm thick inside that), floor top z = 0.
constexpr double kOctreeResolution = 0.05;
constexpr double kRoomInner = 1.2, kRoomOuter = 1.3;
constexpr double kFloorBottom = -0.1, kWallTop = 1.5;
constexpr double kColumnRadius = 0.08, kColumnTop = 1.0;

// Paths (shared layout).
constexpr double kSkimRadius = 0.85;
constexpr double kSlalomHeight = 0.45;
constexpr double kSlalomAmplitude = 0.12;            ///< the path's |y| at a pillar
constexpr double kSlalomPillarX[4] = {-0.45, -0.15, 0.15, 0.45};
constexpr double kSlalomGaps[4] = {0.015, 0.06, 0.035, 0.08};  ///< intended clearances
constexpr double kSlalomMaxBank = 25 * kDegree;
constexpr double kOpenRadius = 0.55;
constexpr double kOpenHeight = 1.4;

// ---------------------------------------------------------------- layout
struct Crate {
  double x, y, yaw, sx, sy, sz, bottom;
  double top() const { return bottom + sz; }
  /// Whether (px, py) is over the crate's footprint grown by `margin`.
  bool covers(double px, double py, double margin = 0) const {
    const double dx = px - x, dy = py - y, c = std::cos(yaw), s = std::sin(yaw);
    return std::abs(c * dx + s * dy) <= sx / 2 + margin &&
           std::abs(-s * dx + c * dy) <= sy / 2 + margin;
  }
  bool contains(const Eigen::Vector3d& p) const {
    return covers(p.x(), p.y()) && p.z() >= bottom && p.z() < top();
  }
  fcl::Transform3d pose() const {
    fcl::Transform3d X = fcl::Transform3d::Identity();
    X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    X.translation() = Eigen::Vector3d(x, y, bottom + sz / 2);
    return X;
  }
};

struct Pillar {
  double x, y, radius, bottom, top;
};

struct Layout {
  std::function<double(double, double)> ground;
  std::vector<Crate> crates;
  std::vector<Pillar> pillars;
  double cell = 0;  ///< the voxel size if voxelised (octree), else 0
};

/// The top of ground and crates at (x, y) (pillars excluded: the low paths avoid
/// them). Voxelised (cells whose centre is inside), a crate reaches up to the top
/// of its highest cell and sideways up to half a cell diagonal beyond its footprint.
double surfaceTop(const Layout& layout, double x, double y) {
  double top = layout.ground(x, y);
  const double margin = layout.cell * std::sqrt(0.5);
  for (const Crate& crate : layout.crates) {
    if (!crate.covers(x, y, margin)) continue;
    top = std::max(top, layout.cell > 0 ? layout.cell * std::ceil(crate.top() / layout.cell - 0.5)
                                        : crate.top());
  }
  return top;
}

/// The highest surface under a disc of radius `reach` about (x, y), sampled.
double footprintTop(const Layout& layout, double x, double y, double reach) {
  double top = surfaceTop(layout, x, y);
  for (int ring = 1; ring <= 6; ++ring) {
    const double rho = reach * ring / 6;
    for (int k = 0; k < 32; ++k) {
      const double phi = 2 * M_PI * k / 32;
      top = std::max(top, surfaceTop(layout, x + rho * std::cos(phi), y + rho * std::sin(phi)));
    }
  }
  return top;
}

struct Hill {
  double x, y, height, width;
};

const std::vector<Hill>& hills() {
  static const std::vector<Hill> made = [] {
    Random random(kSeed);
    std::vector<Hill> h;
    for (int i = 0; i < 10; ++i) {
      h.push_back({random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-0.05, 0.1),
                   random.uniform(0.12, 0.35)});
    }
    return h;
  }();
  return made;
}

double terrainHeight(double x, double y) {
  double h = 0.015 * std::sin(6 * x + 0.5) * std::cos(5 * y - 0.3);
  for (const Hill& hill : hills()) {
    const double d2 = (x - hill.x) * (x - hill.x) + (y - hill.y) * (y - hill.y);
    h += hill.height * std::exp(-d2 / (2 * hill.width * hill.width));
  }
  return h;
}

/// Pillars for the slalom: pillar k at x_k, on the outside of the path's extreme
/// y = -+kSlalomAmplitude there, kSlalomGaps[k] from the level disk's rim; `reach`
/// is how far the pillar extends towards the path. Voxelised (cell > 0), the centre
/// is moved onto the grid, towards the path (the gap shrinks by up to a cell).
std::vector<Pillar> slalomPillars(double radius, double reach, double bottom, double top,
                                  double cell) {
  std::vector<Pillar> pillars;
  for (int k = 0; k < 4; ++k) {
    const double side = k % 2 == 0 ? -1 : 1;
    double y = kSlalomAmplitude + reach + kDiskRadius + kSlalomGaps[k];
    if (cell > 0) y = cell * std::floor(y / cell);
    pillars.push_back({kSlalomPillarX[k], side * y, radius, bottom, top});
  }
  return pillars;
}

/// Crates on the skim circle and one in the middle (on the crossing path), sunk
/// 4 cm into the ground at their centre.
std::vector<Crate> crates(const std::function<double(double, double)>& ground) {
  const double angles[4] = {40, 160, 250, 320};
  const double sizes[5][4] = {// sx, sy, sz, yaw (deg)
                              {0.26, 0.2, 0.14, 20},
                              {0.3, 0.22, 0.2, -35},
                              {0.22, 0.22, 0.12, 10},
                              {0.28, 0.18, 0.17, 60},
                              {0.3, 0.22, 0.2, 15}};
  std::vector<Crate> made;
  for (int i = 0; i < 5; ++i) {
    const double x = i < 4 ? kSkimRadius * std::cos(angles[i] * kDegree) : 0.0;
    const double y = i < 4 ? kSkimRadius * std::sin(angles[i] * kDegree) : -0.05;
    made.push_back({x, y, sizes[i][3] * kDegree, sizes[i][0], sizes[i][1], sizes[i][2],
                    ground(x, y) - 0.04});
  }
  return made;
}

// ---------------------------------------------------------------- the mesh
struct MeshWorld {
  Layout layout;
  std::vector<fcl::Vector3d> vertices;
  std::vector<fcl::Triangle> triangles;
  std::vector<fcl::TriangleP<double>> primitives;  ///< for the brute-force reference
  double bounding_radius = 0;
};

void appendModel(const fcl::BVHModel<fcl::OBBRSSd>& part, MeshWorld& world) {
  const std::size_t offset = world.vertices.size();
  for (int i = 0; i < part.num_vertices; ++i) world.vertices.push_back(part.vertices[i]);
  for (int i = 0; i < part.num_tris; ++i) {
    const fcl::Triangle& t = part.tri_indices[i];
    world.triangles.emplace_back(t[0] + offset, t[1] + offset, t[2] + offset);
  }
}

const MeshWorld& meshWorld() {
  static const MeshWorld world = [] {
    MeshWorld w;
    w.layout.ground = terrainHeight;
    w.layout.crates = crates(terrainHeight);
    w.layout.pillars = slalomPillars(kMeshPillarRadius, kMeshPillarRadius, kMeshPillarBottom,
                                     kMeshPillarTop, 0.0);
    // Terrain: (n + 1)^2 vertices, two triangles per cell.
    const int n = kTerrainCells;
    const double step = 2 * kTerrainHalfSide / n;
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const double x = -kTerrainHalfSide + i * step, y = -kTerrainHalfSide + j * step;
        w.vertices.emplace_back(x, y, terrainHeight(x, y));
      }
    }
    const auto index = [n](int i, int j) { return std::size_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        w.triangles.emplace_back(index(i, j), index(i + 1, j), index(i + 1, j + 1));
        w.triangles.emplace_back(index(i, j), index(i + 1, j + 1), index(i, j + 1));
      }
    }
    for (const Crate& crate : w.layout.crates) {
      fcl::BVHModel<fcl::OBBRSSd> part;
      fcl::generateBVHModel(part, fcl::Boxd(crate.sx, crate.sy, crate.sz), crate.pose());
      appendModel(part, w);
    }
    for (const Pillar& pillar : w.layout.pillars) {
      fcl::BVHModel<fcl::OBBRSSd> part;
      fcl::Transform3d X = fcl::Transform3d::Identity();
      X.translation() = Eigen::Vector3d(pillar.x, pillar.y, (pillar.bottom + pillar.top) / 2);
      fcl::generateBVHModel(part, fcl::Cylinderd(pillar.radius, pillar.top - pillar.bottom), X,
                            kMeshPillarSides, kMeshPillarStacks);
      appendModel(part, w);
    }
    for (const fcl::Triangle& t : w.triangles) {
      w.primitives.emplace_back(w.vertices[t[0]], w.vertices[t[1]], w.vertices[t[2]]);
    }
    for (const fcl::Vector3d& v : w.vertices)
      w.bounding_radius = std::max(w.bounding_radius, v.norm());
    return w;
  }();
  return world;
}

template <typename BV>
std::shared_ptr<fcl::CollisionGeometryd> buildModel(const MeshWorld& world) {
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  model->beginModel(int(world.triangles.size()), int(world.vertices.size()));
  model->addSubModel(world.vertices, world.triangles);
  model->endModel();
  return model;
}

// ---------------------------------------------------------------- the octree
struct OctreeWorld {
  Layout layout;
  std::shared_ptr<fcl::OcTreed> octree;
  std::vector<fcl::Boxd> cell_boxes;          ///< occupied leaves, for the reference
  std::vector<fcl::Transform3d> cell_poses;
  std::size_t voxels = 0;                     ///< occupied 5 cm cells before pruning
  double bounding_radius = 0;
};

double roomFloor(double, double) { return 0.0; }

bool roomSolid(const Layout& layout, const Eigen::Vector3d& p) {
  const double ax = std::abs(p.x()), ay = std::abs(p.y());
  if (ax >= kRoomOuter || ay >= kRoomOuter || p.z() < kFloorBottom || p.z() >= kWallTop) {
    return false;
  }
  if (p.z() < 0) return true;                                  // floor
  if (std::max(ax, ay) >= kRoomInner) return true;             // walls
  for (const Crate& crate : layout.crates)
    if (crate.contains(p)) return true;
  for (const Pillar& column : layout.pillars) {
    const double dx = p.x() - column.x, dy = p.y() - column.y;
    if (dx * dx + dy * dy < column.radius * column.radius && p.z() >= column.bottom &&
        p.z() < column.top) {
      return true;
    }
  }
  return false;
}

const OctreeWorld& octreeWorld() {
  static const OctreeWorld world = [] {
    OctreeWorld w;
    w.layout.ground = roomFloor;
    w.layout.crates = crates(roomFloor);
    w.layout.cell = kOctreeResolution;
    // A column centred on a grid corner: its cells (centres within 8 cm) reach
    // 10 cm along the axes.
    w.layout.pillars = slalomPillars(kColumnRadius, 2 * kOctreeResolution, 0.0, kColumnTop,
                                     kOctreeResolution);
    auto tree = std::make_shared<octomap::OcTree>(kOctreeResolution);
    const int lo = int(std::floor(-kRoomOuter / kOctreeResolution));
    const int hi = int(std::ceil(kRoomOuter / kOctreeResolution));
    const int zlo = int(std::floor(kFloorBottom / kOctreeResolution));
    const int zhi = int(std::ceil(kWallTop / kOctreeResolution));
    for (int kz = zlo; kz < zhi; ++kz) {
      for (int ky = lo; ky < hi; ++ky) {
        for (int kx = lo; kx < hi; ++kx) {
          const Eigen::Vector3d centre = (Eigen::Vector3d(kx, ky, kz).array() + 0.5).matrix() *
                                         kOctreeResolution;
          if (!roomSolid(w.layout, centre)) continue;
          const octomap::OcTreeKey key = tree->coordToKey(centre.x(), centre.y(), centre.z());
          tree->updateNode(key, true, /*lazy_eval=*/true);
          ++w.voxels;
        }
      }
    }
    tree->updateInnerOccupancy();
    tree->prune();
    w.octree = std::make_shared<fcl::OcTreed>(std::shared_ptr<const octomap::OcTree>(tree));
    for (const std::array<double, 6>& box : w.octree->toBoxes()) {
      w.cell_boxes.emplace_back(box[3], box[3], box[3]);
      fcl::Transform3d X = fcl::Transform3d::Identity();
      X.translation() = Eigen::Vector3d(box[0], box[1], box[2]);
      w.cell_poses.push_back(X);
      w.bounding_radius = std::max(w.bounding_radius, X.translation().norm() +
                                                          box[3] * std::sqrt(3.0) / 2);
    }
    return w;
  }();
  return world;
}

// ---------------------------------------------------------------- scenes
enum class Env { mesh, octree };
enum class Scene { mesh_obbrss, mesh_rss, mesh_obb, mesh_aabb, octree };
enum class PathKind { skim, slalom, crossing, open, all };
enum class Variant { disk, sphere, cylinder };
enum class Query { distance, collide };

const char* name(Scene scene) {
  switch (scene) {
    case Scene::mesh_obbrss: return "mesh_obbrss";
    case Scene::mesh_rss: return "mesh_rss";
    case Scene::mesh_obb: return "mesh_obb";
    case Scene::mesh_aabb: return "mesh_aabb";
    case Scene::octree: return "octree";
  }
  return "?";
}
const char* name(PathKind path) {
  switch (path) {
    case PathKind::skim: return "skim";
    case PathKind::slalom: return "slalom";
    case PathKind::crossing: return "crossing";
    case PathKind::open: return "open";
    case PathKind::all: return "all";
  }
  return "?";
}
const char* name(Variant variant) {
  switch (variant) {
    case Variant::disk: return "disk";
    case Variant::sphere: return "sphere";
    case Variant::cylinder: return "cylinder";
  }
  return "?";
}
const char* name(Query query) { return query == Query::distance ? "distance" : "collide"; }

Env envOf(Scene scene) { return scene == Scene::octree ? Env::octree : Env::mesh; }
const Layout& layoutOf(Env env) {
  return env == Env::mesh ? meshWorld().layout : octreeWorld().layout;
}
double boundingRadius(Env env) {
  return env == Env::mesh ? meshWorld().bounding_radius : octreeWorld().bounding_radius;
}

/// The environment as an FCL object at the identity (one per scene, kept).
const fcl::CollisionObjectd& environmentObject(Scene scene) {
  static std::map<Scene, std::unique_ptr<fcl::CollisionObjectd>> cache;
  auto& slot = cache[scene];
  if (!slot) {
    std::shared_ptr<fcl::CollisionGeometryd> geometry;
    switch (scene) {
      case Scene::mesh_obbrss: geometry = buildModel<fcl::OBBRSSd>(meshWorld()); break;
      case Scene::mesh_rss: geometry = buildModel<fcl::RSSd>(meshWorld()); break;
      case Scene::mesh_obb: geometry = buildModel<fcl::OBBd>(meshWorld()); break;
      case Scene::mesh_aabb: geometry = buildModel<fcl::AABBd>(meshWorld()); break;
      case Scene::octree: geometry = octreeWorld().octree; break;
    }
    slot = std::make_unique<fcl::CollisionObjectd>(geometry, fcl::Transform3d::Identity());
  }
  return *slot;
}

// ---------------------------------------------------------------- paths
/// yaw about world Z, then pitch about the body's Y, then bank about its X.
fcl::Transform3d flightPose(const Eigen::Vector3d& centre, double yaw, double pitch,
                            double bank) {
  fcl::Transform3d X = fcl::Transform3d::Identity();
  X.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(bank, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  X.translation() = centre;
  return X;
}

/// How far the disk's rim reaches below its centre: r sin(tilt).
double rimDrop(const fcl::Transform3d& X) {
  const double cos_tilt = std::min(1.0, std::abs(X.linear()(2, 2)));
  return kDiskRadius * std::sqrt(1 - cos_tilt * cos_tilt);
}

std::vector<fcl::Transform3d> makePath(Env env, PathKind path) {
  const Layout& layout = layoutOf(env);
  std::vector<fcl::Transform3d> poses;
  for (int i = 0; i < kPosesPerPath; ++i) {
    const double t = double(i) / kPosesPerPath;
    switch (path) {
      case PathKind::skim: {
        const double theta = 2 * M_PI * t + 0.3;
        const double x = kSkimRadius * std::cos(theta), y = kSkimRadius * std::sin(theta);
        fcl::Transform3d X = flightPose(Eigen::Vector3d(x, y, 0), theta + M_PI / 2,
                                        (10 + 5 * std::sin(4 * M_PI * t)) * kDegree,
                                        -8 * kDegree);
        const double clearance = 0.01 + 0.09 * (0.5 - 0.5 * std::cos(6 * M_PI * t));
        X.translation().z() =
            footprintTop(layout, x, y, kDiskRadius + 0.01) + rimDrop(X) + clearance;
        poses.push_back(X);
        break;
      }
      case PathKind::slalom: {
        const double x = -0.75 + 1.5 * t;
        const double phase = M_PI * (x - kSlalomPillarX[0]) / 0.3;
        const double y = -kSlalomAmplitude * std::cos(phase);
        const double dy_dx = kSlalomAmplitude * (M_PI / 0.3) * std::sin(phase);
        poses.push_back(flightPose(Eigen::Vector3d(x, y, kSlalomHeight + 0.03 * std::sin(phase)),
                                   std::atan(dy_dx), 8 * kDegree,
                                   -kSlalomMaxBank * std::cos(phase)));
        break;
      }
      case PathKind::crossing: {
        // Start high, through the middle crate's centre, end 2 cm under the ground.
        const Crate& middle = layout.crates.back();
        const Eigen::Vector3d a(-0.85, -0.55, 0.35);
        const Eigen::Vector3d b(middle.x, middle.y, middle.bottom + middle.sz / 2);
        const Eigen::Vector3d c(0.85, 0.45, layout.ground(0.85, 0.45) - 0.02);
        const Eigen::Vector3d p = t < 0.5 ? a + (b - a) * (2 * t) : b + (c - b) * (2 * t - 1);
        const Eigen::Vector3d d = t < 0.5 ? b - a : c - b;
        poses.push_back(flightPose(p, std::atan2(d.y(), d.x()), 12 * kDegree, 4 * kDegree));
        break;
      }
      case PathKind::open: {
        const double theta = 2 * M_PI * t;
        const Eigen::Vector3d p(kOpenRadius * std::cos(theta), kOpenRadius * std::sin(theta),
                                kOpenHeight + 0.05 * std::sin(4 * M_PI * t));
        poses.push_back(flightPose(p, theta + M_PI / 2, 12 * kDegree, -10 * kDegree));
        break;
      }
      case PathKind::all: break;
    }
  }
  return poses;
}

const std::vector<fcl::Transform3d>& flightPath(Env env, PathKind path) {
  static std::map<std::pair<Env, PathKind>, std::vector<fcl::Transform3d>> cache;
  auto it = cache.find({env, path});
  if (it == cache.end()) {
    std::vector<fcl::Transform3d> poses;
    if (path == PathKind::all) {
      for (PathKind part : {PathKind::skim, PathKind::slalom, PathKind::crossing, PathKind::open}) {
        const auto& piece = flightPath(env, part);
        poses.insert(poses.end(), piece.begin(), piece.end());
      }
    } else {
      poses = makePath(env, path);
    }
    it = cache.emplace(std::make_pair(env, path), std::move(poses)).first;
  }
  return it->second;
}

// ---------------------------------------------------------------- reference
struct Exact {
  double distance;      ///< brute-force minimum over every triangle / occupied cell
  bool intersects;      ///< some triangle / cell intersects the disk
  double deepest;       ///< largest penetration_depth among those (0 if none)
  double scale;         ///< r + R_E + |c_D|
};

template <typename Shape>
void accumulate(const fcl::Transform3d& X_WD, const Shape& shape, const fcl::Transform3d& X_WS,
                Exact& exact) {
  const double d = fcl_disk::diskShapeDistance(kDiskRadius, X_WD, shape, X_WS).distance;
  exact.distance = std::min(exact.distance, d);
  if (d == 0) {
    fcl_disk::DiskContact<double> contact;
    if (fcl_disk::diskShapeIntersect(kDiskRadius, X_WD, shape, X_WS, &contact)) {
      exact.intersects = true;
      exact.deepest = std::max(exact.deepest, contact.penetration_depth);
    }
  }
}

Exact exactAnswer(Env env, const fcl::Transform3d& X_WD) {
  Exact exact{std::numeric_limits<double>::infinity(), false, 0.0,
              kDiskRadius + boundingRadius(env) + X_WD.translation().norm()};
  if (env == Env::mesh) {
    const fcl::Transform3d identity = fcl::Transform3d::Identity();
    for (const fcl::TriangleP<double>& triangle : meshWorld().primitives)
      accumulate(X_WD, triangle, identity, exact);
  } else {
    const OctreeWorld& world = octreeWorld();
    for (std::size_t i = 0; i < world.cell_boxes.size(); ++i)
      accumulate(X_WD, world.cell_boxes[i], world.cell_poses[i], exact);
  }
  return exact;
}

/// The reference on every kCheckStride-th pose of a path (index -> answer).
const std::map<std::size_t, Exact>& reference(Env env, PathKind path) {
  static std::map<std::pair<Env, PathKind>, std::map<std::size_t, Exact>> cache;
  auto it = cache.find({env, path});
  if (it == cache.end()) {
    std::map<std::size_t, Exact> answers;
    if (path == PathKind::all) {
      std::size_t offset = 0;
      for (PathKind part : {PathKind::skim, PathKind::slalom, PathKind::crossing, PathKind::open}) {
        for (const auto& [k, exact] : reference(env, part)) answers.emplace(offset + k, exact);
        offset += flightPath(env, part).size();
      }
    } else {
      const auto& poses = flightPath(env, path);
      for (std::size_t k = 0; k < poses.size(); k += kCheckStride)
        answers.emplace(k, exactAnswer(env, poses[k]));
    }
    it = cache.emplace(std::make_pair(env, path), std::move(answers)).first;
  }
  return it->second;
}

// ---------------------------------------------------------------- queries
bool g_keep_failed_timings = false;

std::shared_ptr<fcl::CollisionGeometryd> movingShape(Variant variant) {
  switch (variant) {
    case Variant::disk: return std::make_shared<fcl_disk::Diskd>(kDiskRadius);
    case Variant::sphere: return std::make_shared<fcl::Sphered>(kDiskRadius);
    case Variant::cylinder: return std::make_shared<fcl::Cylinderd>(kDiskRadius, 0.0);
  }
  return nullptr;
}

/// One query: the distance (distance), or 1 / 0 for contact / none (collide).
inline double runQuery(Query query, const fcl::CollisionObjectd& mover,
                       const fcl::CollisionObjectd& environment) {
  if (query == Query::distance) {
    fcl::DistanceRequestd request;
    fcl::DistanceResultd result;
    fcl::distance(&mover, &environment, request, result);
    benchmark::DoNotOptimize(result);
    return result.min_distance;
  }
  fcl::CollisionRequestd request;
  request.num_max_contacts = 1;
  fcl::CollisionResultd result;
  const std::size_t contacts = fcl::collide(&mover, &environment, request, result);
  benchmark::DoNotOptimize(result);
  return contacts > 0 ? 1.0 : 0.0;
}

bool inContact(Query query, double answer) {
  return query == Query::distance ? answer <= 0 : answer > 0;
}

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return std::nan("");
  const std::size_t k = std::min(values.size() - 1, std::size_t(q * (values.size() - 1) + 0.5));
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.end());
  return values[k];
}

struct CheckOutcome {
  long failures = 0;         ///< disk: beyond tolerance; cylinder: verdict mismatches
  double max_err_over_scale = 0;
  double max_abs_diff = 0;
  std::string first_failure;
};

CheckOutcome check(Query query, Variant variant, Env env, PathKind path,
                   const std::vector<double>& answers) {
  CheckOutcome outcome;
  for (const auto& [k, exact] : reference(env, path)) {
    const double band = kCheckTolerance * exact.scale;
    if (query == Query::distance) {
      const double got = variant == Variant::disk ? answers[k] : std::max(answers[k], 0.0);
      const double diff = std::abs(got - exact.distance);
      outcome.max_abs_diff = std::max(outcome.max_abs_diff, diff);
      outcome.max_err_over_scale = std::max(outcome.max_err_over_scale, diff / exact.scale);
      if (!(diff <= band)) {
        if (outcome.failures++ == 0) {
          std::ostringstream message;
          message.precision(17);
          message << "pose " << k << ": distance " << answers[k] << ", brute force "
                  << exact.distance << " (|diff| = " << diff << " > " << band << ")";
          outcome.first_failure = message.str();
        }
      }
    } else {
      const bool got = answers[k] > 0;
      const bool ambiguous = exact.distance <= band && exact.deepest <= band;
      if (got != exact.intersects && !ambiguous) {
        if (outcome.failures++ == 0) {
          std::ostringstream message;
          message.precision(17);
          message << "pose " << k << ": collide says " << (got ? "contact" : "none")
                  << ", brute force " << (exact.intersects ? "contact" : "none")
                  << " (distance " << exact.distance << ", depth " << exact.deepest << ")";
          outcome.first_failure = message.str();
        }
      }
    }
  }
  return outcome;
}

void environmentBenchmark(benchmark::State& state, Query query, Scene scene, PathKind path,
                          Variant variant) {
  const Env env = envOf(scene);
  const std::vector<fcl::Transform3d>& poses = flightPath(env, path);
  const fcl::CollisionObjectd& environment = environmentObject(scene);
  const auto shape = movingShape(variant);
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> movers;
  for (const fcl::Transform3d& X : poses)
    movers.push_back(std::make_unique<fcl::CollisionObjectd>(shape, X));
  const std::size_t n = poses.size();
  std::vector<std::vector<float>> samples(n);
  for (auto& s : samples) s.reserve(256);
  std::vector<double> answers(n, std::nan(""));

  // A pair FCL has no distance function for (Debian's libfcl 0.7: Sphere or
  // Cylinder against an AABB or OBB mesh) prints "not supported" and leaves
  // min_distance at max(): not timed (one query, one warning).
  if (query == Query::distance &&
      runQuery(query, *movers[0], environment) == std::numeric_limits<double>::max()) {
    state.SkipWithError("no answer: FCL left min_distance at its initial max()");
    return;
  }

  for (auto _ : state) {
    for (std::size_t k = 0; k < n; ++k) {
      const Clock::time_point start = Clock::now();
      answers[k] = runQuery(query, *movers[k], environment);
      const Clock::time_point stop = Clock::now();
      samples[k].push_back(float(std::chrono::duration<double, std::nano>(stop - start).count()));
    }
    benchmark::ClobberMemory();
  }

  // Per pose: the median over the sweeps; then over the poses.
  std::vector<double> per_pose(n);
  for (std::size_t k = 0; k < n; ++k) {
    std::vector<double> s(samples[k].begin(), samples[k].end());
    per_pose[k] = quantile(std::move(s), 0.5);
  }
  long contacts = 0;
  for (double answer : answers) contacts += inContact(query, answer);

  state.counters["poses"] = double(n);
  state.counters["median_ns"] = quantile(per_pose, 0.5);
  state.counters["p99_ns"] = quantile(per_pose, 0.99);
  state.counters["per_query"] = benchmark::Counter(
      double(n), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["contact"] = double(contacts) / double(n);

  // The reference's view of the path (the same for every variant).
  const auto& exact = reference(env, path);
  std::vector<double> clearances;
  long exact_contacts = 0;
  for (const auto& [k, e] : exact) {
    clearances.push_back(e.distance);
    exact_contacts += e.intersects;
  }
  state.counters["checked"] = double(exact.size());
  state.counters["exact_contact"] = double(exact_contacts) / double(exact.size());
  state.counters["exact_min_mm"] = 1e3 * quantile(clearances, 0.0);
  state.counters["exact_median_mm"] = 1e3 * quantile(clearances, 0.5);

  if (variant == Variant::sphere) return;
  const CheckOutcome outcome = check(query, variant, env, path, answers);
  if (variant == Variant::cylinder) {
    if (query == Query::distance) {
      state.counters["max_abs_diff_vs_exact"] = outcome.max_abs_diff;
    } else {
      state.counters["verdict_mismatches"] = double(outcome.failures);
    }
    return;
  }
  state.counters["check_failures"] = double(outcome.failures);
  if (query == Query::distance) state.counters["max_err_over_scale"] = outcome.max_err_over_scale;
  if (outcome.failures > 0 && !g_keep_failed_timings) {
    state.SkipWithError((std::to_string(outcome.failures) + " of " + std::to_string(exact.size()) +
                         " checked poses differ from the brute-force reference; first: " +
                         outcome.first_failure)
                            .c_str());
  }
}

void registerAll() {
  const Scene distance_scenes[] = {Scene::mesh_obbrss, Scene::mesh_rss, Scene::mesh_obb,
                                   Scene::mesh_aabb, Scene::octree};
  const Scene collide_scenes[] = {Scene::mesh_obbrss, Scene::mesh_rss, Scene::mesh_obb,
                                  Scene::mesh_aabb, Scene::octree};
  const PathKind paths[] = {PathKind::skim, PathKind::slalom, PathKind::crossing, PathKind::open,
                            PathKind::all};
  const Variant variants[] = {Variant::disk, Variant::sphere, Variant::cylinder};
  const auto add = [&](Query query, Scene scene) {
    for (PathKind path : paths) {
      for (Variant variant : variants) {
        const std::string title = std::string(name(query)) + "/" + name(scene) + "/" +
                                  name(path) + "/" + name(variant);
        benchmark::RegisterBenchmark(title.c_str(), environmentBenchmark, query, scene, path,
                                     variant)
            ->Unit(benchmark::kMillisecond);
      }
    }
  };
  for (Scene scene : distance_scenes) add(Query::distance, scene);
  for (Scene scene : collide_scenes) add(Query::collide, scene);
}

/// Prints the environments' sizes and the paths' clearances (stderr), once.
void describeScenes() {
  const MeshWorld& mesh = meshWorld();
  const OctreeWorld& octree = octreeWorld();
  double low = std::numeric_limits<double>::max(), high = -low;
  for (int i = 0; i < (kTerrainCells + 1) * (kTerrainCells + 1); ++i) {
    low = std::min(low, mesh.vertices[std::size_t(i)].z());
    high = std::max(high, mesh.vertices[std::size_t(i)].z());
  }
  std::fprintf(stderr,
               "bench_environment: mesh %zu triangles, %zu vertices, terrain heights %.3f..%.3f "
               "m, bounding radius %.3f m; octree %zu occupied leaves (%zu voxels of %.3g m "
               "before pruning), bounding radius %.3f m\n",
               mesh.triangles.size(), mesh.vertices.size(), low, high, mesh.bounding_radius,
               octree.cell_boxes.size(), octree.voxels, kOctreeResolution,
               octree.bounding_radius);
}

/// --calls QUERY/SCENE: the disk's queries on the whole flight, kCallPasses sweeps.
int runCalls(const std::string& which) {
  for (Query query : {Query::distance, Query::collide}) {
    for (Scene scene : {Scene::mesh_obbrss, Scene::mesh_rss, Scene::mesh_obb, Scene::mesh_aabb,
                        Scene::octree}) {
      if (which != std::string(name(query)) + "/" + name(scene)) continue;
      const fcl::CollisionObjectd& environment = environmentObject(scene);
      const auto shape = movingShape(Variant::disk);
      std::vector<std::unique_ptr<fcl::CollisionObjectd>> movers;
      for (const fcl::Transform3d& X : flightPath(envOf(scene), PathKind::all))
        movers.push_back(std::make_unique<fcl::CollisionObjectd>(shape, X));
      double sum = 0.0;
      for (int pass = 0; pass < kCallPasses; ++pass) {
        for (const auto& mover : movers) sum += runQuery(query, *mover, environment);
      }
      std::printf("%zu queries, sum of answers %.17g\n", movers.size() * kCallPasses, sum);
      return 0;
    }
  }
  std::fprintf(stderr, "--calls takes QUERY/SCENE: distance or collide, and one of mesh_obbrss, "
                       "mesh_rss, mesh_obb, mesh_aabb, octree\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  // Our own flags, removed before Google Benchmark sees the arguments.
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--calls") == 0 && i + 1 < argc) {
      fcl_disk::registerDiskFunctions(fcl_disk::DiskDistanceMethod::exact);
      return runCalls(argv[i + 1]);
    }
    if (std::strcmp(argv[i], "--keep_failed_timings") == 0) {
      g_keep_failed_timings = true;
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  fcl_disk::registerDiskFunctions(fcl_disk::DiskDistanceMethod::exact);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  describeScenes();
  registerAll();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
