#include "core/mesh/point_fitting.h"

#include <cmath>
#include <iostream>
#include <random>

#include "core/mesh/mesh_check.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/smooth_surface.h"
#include "core/mesh/surface_nets.h"
#include "gtest/gtest.h"
#include "tests/mesh/mesh_builders.h"
#include "tests/mesh/surface_expectations.h"
#include "tests/mesh/test_grids.h"
#include "tests/support/cpu_time_cancel.h"

namespace membrane {
namespace {

using namespace membrane::testing;

// A sampled sphere in model units: voxel 0.05, radius 11 voxels, centred in a 32^3 grid.
struct SphereCase {
  static constexpr double kVoxel = 0.05;
  static constexpr double kRadius = 11 * kVoxel;
  const std::array<double, 3> centre = {16 * kVoxel + 0.013, 16 * kVoxel - 0.007,
                                        16 * kVoxel + 0.004};
  const std::vector<Point3f> points = SpherePoints(20000, centre, kRadius, 3);
  const VoxelGrid grid = SampledSphereGrid(32, kVoxel, centre, kRadius, points);

  double MeanDistance(const TriangleMesh& m) const {
    double sum = 0;
    for (const Point3f& p : m.vertices) {
      const double dx = p[0] - centre[0], dy = p[1] - centre[1], dz = p[2] - centre[2];
      sum += std::fabs(std::sqrt(dx * dx + dy * dy + dz * dz) - kRadius);
    }
    return sum / m.vertices.size();
  }
};

// A torus sampled uniformly by area in model units: voxel 0.05, radii 7 and 4 voxels, in a
// 32^3 grid. Its inner half is saddle-shaped, and with the tube thicker than the hole's radius
// the concave bend dominates there (principal curvatures 1/4 and -1/3 at the inner equator).
struct TorusCase {
  static constexpr double kVoxel = 0.05;
  static constexpr double kBig = 7 * kVoxel, kSmall = 4 * kVoxel;
  const std::array<double, 3> centre = {16 * kVoxel + 0.011, 16 * kVoxel - 0.006,
                                        16 * kVoxel + 0.003};
  const std::vector<Point3f> points = Sample(40000);
  const VoxelGrid grid = Grid();

  std::vector<Point3f> Sample(int count) const {
    // Area density is proportional to big + small cos(v): rejection on v.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> angle(0, 2 * M_PI), unit(0, 1);
    std::vector<Point3f> out;
    while (static_cast<int>(out.size()) < count) {
      const double u = angle(rng), v = angle(rng);
      if (unit(rng) * (kBig + kSmall) > kBig + kSmall * std::cos(v)) continue;
      const double r = kBig + kSmall * std::cos(v);
      out.push_back({static_cast<float>(centre[0] + r * std::cos(u)),
                     static_cast<float>(centre[1] + r * std::sin(u)),
                     static_cast<float>(centre[2] + kSmall * std::sin(v))});
    }
    return out;
  }
  VoxelGrid Grid() const {
    VoxelGrid g = OutsideGrid(32, kVoxel);
    for (const Point3f& p : points)
      g.set(Coord{static_cast<int>(std::floor(p[0] / kVoxel)),
                  static_cast<int>(std::floor(p[1] / kVoxel)),
                  static_cast<int>(std::floor(p[2] / kVoxel))},
            kInsideSoft);
    MarkSolid(g,
              [&](int x, int y, int z) { return SignedDistance(g.Center(Coord{x, y, z})) <= 0; });
    FillCavities(g);
    ClassifyMembrane(g);
    return g;
  }
  // Negative inside the solid torus.
  double SignedDistance(const std::array<double, 3>& p) const {
    const double dx = p[0] - centre[0], dy = p[1] - centre[1], dz = p[2] - centre[2];
    const double ring = std::sqrt(dx * dx + dy * dy) - kBig;
    return std::sqrt(ring * ring + dz * dz) - kSmall;
  }
};

SmoothSurfaceOptions FitWith(bool quadric) {
  SmoothSurfaceOptions options;
  options.fit_options.quadric = quadric;
  return options;
}

TriangleMesh Surface(const VoxelGrid& grid, absl::Span<const Point3f> points, bool fit,
                     SmoothSurfaceOptions options = {}, SmoothSurfaceStats* stats = nullptr) {
  options.fit = fit;
  absl::StatusOr<TriangleMesh> mesh = SmoothSurface(grid, points, options, stats);
  EXPECT_TRUE(mesh.ok()) << mesh.status();
  return mesh.ok() ? *std::move(mesh) : TriangleMesh{};
}

TEST(PointFitting, FittedSphereIsCloserToTheAnalyticSphereThanUnfitted) {
  const SphereCase s;
  const double unfitted = s.MeanDistance(Surface(s.grid, s.points, false));
  const double fitted = s.MeanDistance(Surface(s.grid, s.points, true));
  std::cout << "mean distance to the sphere, voxels: unfitted " << unfitted / s.kVoxel
            << ", fitted " << fitted / s.kVoxel << "\n";
  EXPECT_LT(fitted, 0.5 * unfitted);
  EXPECT_LT(fitted, 0.1 * s.kVoxel);
}

// The rounding bias: a plane through the points near a vertex of a curved surface lies on the
// inner side of the curvature; the quadric follows it.
TEST(PointFitting, QuadricFitFollowsTheSphereWhereThePlaneFitRoundsIt) {
  const SphereCase s;
  SmoothSurfaceStats stats;
  const TriangleMesh curved = Surface(s.grid, s.points, true, FitWith(true), &stats);
  const double plane = s.MeanDistance(Surface(s.grid, s.points, true, FitWith(false)));
  const double quadric = s.MeanDistance(curved);
  std::cout << "mean distance to the sphere, voxels: plane " << plane / s.kVoxel << ", quadric "
            << quadric / s.kVoxel << "\n";
  EXPECT_LT(quadric, 0.015 * s.kVoxel);
  EXPECT_GT(plane, 0.03 * s.kVoxel);  // the bound is one the plane fit misses
  EXPECT_GT(stats.fit.quadric_targets, 10 * stats.fit.plane_targets);
  ExpectValidSurface(curved, 1, {0});
}

TEST(PointFitting, QuadricFitFollowsTheTorusOnItsConvexAndSaddleSides) {
  const TorusCase t;
  const auto mean_distance = [&t](const TriangleMesh& m) {
    double sum = 0;
    for (const Point3f& p : m.vertices) sum += std::fabs(t.SignedDistance({p[0], p[1], p[2]}));
    return sum / m.vertices.size();
  };
  SmoothSurfaceStats stats;
  const TriangleMesh curved = Surface(t.grid, t.points, true, FitWith(true), &stats);
  const double quadric = mean_distance(curved);
  const double plane = mean_distance(Surface(t.grid, t.points, true, FitWith(false)));
  std::cout << "mean distance to the torus, voxels: plane " << plane / t.kVoxel << ", quadric "
            << quadric / t.kVoxel << "\n";
  // The quadric's residue is the torus's quartic terms over a 2-voxel neighbourhood where a
  // curvature radius is 3 voxels; the plane misses by the quadratic ones.
  EXPECT_LT(quadric, 0.02 * t.kVoxel);
  EXPECT_GT(plane, 0.05 * t.kVoxel);
  EXPECT_GT(stats.fit.quadric_targets, 10 * stats.fit.plane_targets);
  ExpectValidSurface(curved, 1, {1});
}

TEST(PointFitting, SparsePointsTakeTheWiderQuadricOrFallBackToThePlane) {
  // About one point per 2 voxel faces: most vertices have fewer points within 2 voxels than a
  // quadric needs. The wider try (4 voxels) finds enough; without it they take a plane (or an
  // umbrella step), rounded like the plane fit of dense points.
  const SphereCase dense;
  const std::vector<Point3f> sparse = SpherePoints(900, dense.centre, dense.kRadius, 5);
  const VoxelGrid grid =
      SampledSphereGrid(32, dense.kVoxel, dense.centre, dense.kRadius, sparse);
  for (bool wide : {true, false}) {
    SmoothSurfaceOptions options = FitWith(true);
    if (!wide) options.fit_options.sparse_radius = 0;
    SmoothSurfaceStats stats;
    const TriangleMesh m = Surface(grid, sparse, true, options, &stats);
    const double distance = dense.MeanDistance(m);
    std::cout << "sparse sphere, wider try " << wide << ": quadric " << stats.fit.quadric_targets
              << ", plane " << stats.fit.plane_targets << ", umbrella "
              << stats.fit.umbrella_targets << " targets; mean distance "
              << distance / dense.kVoxel << " voxels\n";
    if (wide) {
      EXPECT_GT(stats.fit.quadric_targets,
                10 * (stats.fit.plane_targets + stats.fit.umbrella_targets));
      EXPECT_LT(distance, 0.02 * dense.kVoxel);
    } else {
      EXPECT_GT(stats.fit.plane_targets, stats.fit.quadric_targets);
      EXPECT_LT(distance, 0.25 * dense.kVoxel);
    }
    ExpectValidSurface(m, 1, {0});
  }
}

TEST(PointFitting, TooFewPointsForEitherQuadricKeepEveryPromise) {
  // One point per 10 voxel faces: the wider try finds too few as well; plane and umbrella
  // targets, and a valid surface.
  const SphereCase dense;
  const std::vector<Point3f> sparse = SpherePoints(150, dense.centre, dense.kRadius, 6);
  const VoxelGrid grid =
      SampledSphereGrid(32, dense.kVoxel, dense.centre, dense.kRadius, sparse);
  SmoothSurfaceStats stats;
  const TriangleMesh m = Surface(grid, sparse, true, FitWith(true), &stats);
  EXPECT_GT(stats.fit.umbrella_targets, stats.fit.quadric_targets);
  ExpectValidSurface(m, 1, {0});
}

TEST(PointFitting, FittedVerticesStayWithinTheirVoxelBound) {
  const SphereCase s;
  const TriangleMesh unfitted = Surface(s.grid, s.points, false);
  const TriangleMesh fitted = Surface(s.grid, s.points, true);
  ASSERT_EQ(unfitted.vertices.size(), fitted.vertices.size());
  const double bound = FitOptions{}.max_offset * s.kVoxel * (1 + 1e-6);
  for (size_t v = 0; v < fitted.vertices.size(); ++v) {
    const auto& a = fitted.vertices[v];
    const auto& b = unfitted.vertices[v];
    const double d = std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                               (a[2] - b[2]) * (a[2] - b[2]));
    ASSERT_LE(d, bound) << "vertex " << v;
  }
}

TEST(PointFitting, FittedSphereKeepsEverySurfacePromise) {
  const SphereCase s;
  ExpectValidSurface(Surface(s.grid, s.points, true), 1, {0});
}

TEST(PointFitting, FittedTorusKeepsGenusOne) {
  // Points on the analytic torus, solid = voxels inside it plus voxels holding points.
  const double l = 1.0, big = 9, small = 3.5, c = 16;
  std::vector<Point3f> points;
  for (int i = 0; i < 400; ++i)
    for (int j = 0; j < 60; ++j) {
      const double u = 2 * M_PI * i / 400, v = 2 * M_PI * j / 60;
      const double r = big + small * std::cos(v);
      points.push_back({static_cast<float>(c + r * std::cos(u)),
                        static_cast<float>(c + r * std::sin(u)),
                        static_cast<float>(c + small * std::sin(v))});
    }
  VoxelGrid g = OutsideGrid(32, l);
  for (const Point3f& p : points) g.set(Coord{int(p[0]), int(p[1]), int(p[2])}, kInsideSoft);
  MarkSolid(g, [&](int x, int y, int z) {
    const double dx = x + 0.5 - c, dy = y + 0.5 - c, dz = z + 0.5 - c;
    const double ring = std::sqrt(dx * dx + dy * dy) - big;
    return ring * ring + dz * dz <= small * small;
  });
  ExpectValidSurface(Surface(g, points, true), 1, {1});
}

TEST(PointFitting, WithoutPointsOnlySmoothsAndKeepsPromises) {
  const TriangleMesh m = Surface(BallGrid(24, 8.3), {}, true);
  ExpectValidSurface(m, 1, {0});
}

TEST(PointFitting, SmoothSurfaceOfRandomSolidsKeepsEveryPromise) {
  // Odd voxel configurations, where the raw nets sometimes cross itself and the fit's first
  // pass has to repair it toward the fallback; points on the voxel centres of the boundary.
  for (uint32_t seed = 1; seed <= 12; ++seed) {
    const VoxelGrid g = RandomSolidGrid(14, 0.45, seed);
    std::vector<Point3f> points;
    for (int64_t i = 0; i < g.size(); ++i)
      if (IsBoundary(g.at(i))) {
        const auto c = g.Center(g.CoordOf(i));
        points.push_back({float(c[0]), float(c[1]), float(c[2])});
      }
    SmoothSurfaceOptions options;
    options.remove_loose_sheets = false;
    options.fill_caves = false;
    absl::StatusOr<TriangleMesh> mesh = SmoothSurface(g, points, options);
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    const MeshReport r = CheckMesh(*mesh);
    ASSERT_TRUE(r.closed && r.manifold && r.oriented && r.positive_volume)
        << "seed " << seed << " " << MeshReportToJson(r);
    ASSERT_EQ(r.self_intersections, 0) << "seed " << seed;
  }
}

TEST(PointFitting, RepairsInputCrossingsTowardTheFallback) {
  // An input that crosses itself: a ball's surface nets (clean: the fallback) with three
  // vertices pushed through the ball and out of its far side. With the moves switched off
  // (max_offset 0) only the fallback repair can clean it. (Raw surface nets of random solids
  // cannot serve: with exact predicates none of 1600 crosses itself.)
  UnrepairedSurfaceNets nets = SurfaceNetsBeforeRepair(BallGrid(16, 5.3));
  ASSERT_TRUE(FindIntersectingFaces(nets.mesh).empty());
  for (size_t v : {size_t{0}, nets.mesh.vertices.size() / 3, 2 * nets.mesh.vertices.size() / 3}) {
    Point3f& p = nets.mesh.vertices[v];
    for (int k = 0; k < 3; ++k) p[k] = 8.0f - 1.3f * (p[k] - 8.0f);  // the grid's centre is 8
  }
  ASSERT_FALSE(FindIntersectingFaces(nets.mesh).empty());
  FitOptions still;
  still.max_offset = 0;
  const absl::StatusOr<FitStats> stats =
      FitToPoints(nets.mesh, 1.0, {}, still, CancelToken::Never(), &nets.fallback);
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_GT(stats->repaired_vertices, 0);
  const MeshReport r = CheckMesh(nets.mesh);
  EXPECT_TRUE(r.closed && r.manifold && r.oriented) << MeshReportToJson(r);
  EXPECT_EQ(r.self_intersections, 0);
  EXPECT_EQ(r.degenerate_faces, 0);
  EXPECT_TRUE(stats->crossings_known);
  EXPECT_TRUE(stats->crossings.empty());
}

TEST(PointFitting, ListsTheCrossingsThatAGridTooCoarseLeaves) {
  // On a 4-bit grid (a step of about 1.1 voxels) no repair keeps every face apart: the fit's
  // list of what still crosses is what a mesh check relies on, so it must be exactly what a
  // search of the whole mesh finds (also at 5 and 6 bits, whose repairs carry crossings over
  // many searches while a few vertices back off); and with nothing left to repair, an empty
  // list.
  for (int bits : {4, 5, 6, 16}) {
    UnrepairedSurfaceNets nets = SurfaceNetsBeforeRepair(BallGrid(16, 5.3));
    FitOptions options;
    options.output_grid = GridOverBox(bits, {0, 0, 0}, {16, 16, 16}, 1e-6);
    const absl::StatusOr<FitStats> stats =
        FitToPoints(nets.mesh, 1.0, {}, options, CancelToken::Never(), &nets.fallback);
    ASSERT_TRUE(stats.ok()) << stats.status();
    EXPECT_TRUE(stats->crossings_known);
    EXPECT_EQ(stats->crossings, FindIntersectingFaces(nets.mesh)) << bits << " bits";
    if (bits == 4) {
      EXPECT_FALSE(stats->crossings.empty());
    } else if (bits == 16) {
      EXPECT_TRUE(stats->crossings.empty());
    }
  }
}

TEST(PointFitting, RejectsNonPositiveVoxelSize) {
  TriangleMesh m = SurfaceNets(BallGrid(12, 3.5));
  EXPECT_EQ(FitToPoints(m, 0.0, {}).status().code(), absl::StatusCode::kInvalidArgument);
  FitOptions bad;
  bad.rounds = -1;
  EXPECT_EQ(FitToPoints(m, 1.0, {}, bad).status().code(), absl::StatusCode::kInvalidArgument);
  FitOptions few_points;
  few_points.crease_limits.min_side_points = 0;
  const absl::Status creases = FitToPoints(m, 1.0, {}, few_points).status();
  EXPECT_EQ(creases.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(creases.message().find("crease limits out of range"), std::string::npos)
      << creases.message();
}

TEST(PointFitting, StopsWhenCancelled) {
  TriangleMesh m = SurfaceNets(BallGrid(24, 8.3));
  CancelToken cancel;
  cancel.Cancel();
  const absl::StatusOr<FitStats> stats = FitToPoints(m, 1.0, {}, {}, cancel);
  EXPECT_EQ(stats.status().code(), absl::StatusCode::kCancelled);
  const MeshReport r = CheckMesh(m);
  EXPECT_TRUE(r.closed && r.manifold && r.oriented);
  EXPECT_EQ(r.self_intersections, 0);
}

TEST(PointFitting, MeshIsTheSameForAnyThreadCount) {
  // The slabs of a phase are independent, so the result must not depend on how many run side
  // by side: bit for bit, on a sphere with its points and on a torus without (umbrella steps).
  const SphereCase s;
  struct Case {
    VoxelGrid grid;
    std::vector<Point3f> points;
  };
  const Case cases[] = {{s.grid, s.points}, {SolidTorusGrid(48, 14.0, 5.0), {}}};
  for (const Case& c : cases) {
    std::vector<TriangleMesh> meshes;
    std::vector<FitStats> stats;
    for (int threads : {1, 2, 3, 8}) {
      SmoothSurfaceOptions options;
      options.fit_options.threads = threads;
      SmoothSurfaceStats st;
      absl::StatusOr<TriangleMesh> m = SmoothSurface(c.grid, c.points, options, &st);
      ASSERT_TRUE(m.ok()) << m.status();
      meshes.push_back(*std::move(m));
      stats.push_back(st.fit);
    }
    ASSERT_GT(stats[0].moves, 100);
    for (size_t i = 1; i < meshes.size(); ++i) {
      EXPECT_EQ(meshes[i].faces, meshes[0].faces);
      EXPECT_TRUE(meshes[i].vertices == meshes[0].vertices) << "run " << i;
      EXPECT_EQ(stats[i].moves, stats[0].moves);
      EXPECT_EQ(stats[i].refused, stats[0].refused);
      EXPECT_EQ(stats[i].quadric_targets, stats[0].quadric_targets);
      EXPECT_EQ(stats[i].plane_targets, stats[0].plane_targets);
    }
    ExpectValidSurface(meshes.back(), 1, {c.points.empty() ? 1 : 0});
  }
}

TEST(PointFitting, FacesLongerThanASlabFitAsOneSlabOnAnyThreadCount) {
  // A coarse torus whose faces span many 4-voxel slabs at this voxel size: the slabs would not
  // be independent, so the fit takes the whole mesh as one slab, and threads change nothing.
  std::vector<TriangleMesh> meshes;
  for (int threads : {1, 4}) {
    TriangleMesh m = TorusMesh(24, 12, 1.0f, 0.35f);
    FitOptions options;
    options.threads = threads;
    const absl::StatusOr<FitStats> stats = FitToPoints(m, 0.02, {}, options);
    ASSERT_TRUE(stats.ok()) << stats.status();
    EXPECT_GT(stats->moves, 0);
    meshes.push_back(std::move(m));
  }
  EXPECT_TRUE(meshes[0].vertices == meshes[1].vertices);
  const MeshReport r = CheckMesh(meshes[1]);
  EXPECT_TRUE(r.closed && r.manifold && r.oriented) << MeshReportToJson(r);
  EXPECT_EQ(r.self_intersections, 0);
}

TEST(PointFitting, SetUpOnRangesGivesTheSameFit) {
  // 2^16 vertices and more: the fit's set-up (the vertices' stars, the snap, the slabs) runs
  // on ranges on the threads; bit for bit the one-thread fit.
  const UnrepairedSurfaceNets nets = SurfaceNetsBeforeRepair(BallGrid(150, 68.3));
  ASSERT_GE(nets.mesh.vertices.size(), size_t{1} << 16);
  std::vector<TriangleMesh> meshes;
  std::vector<FitStats> stats;
  for (int threads : {1, 3}) {
    TriangleMesh m = nets.mesh;
    FitOptions options;
    options.threads = threads;
    const absl::StatusOr<FitStats> st = FitToPoints(m, 1.0, {}, options);
    ASSERT_TRUE(st.ok()) << st.status();
    meshes.push_back(std::move(m));
    stats.push_back(*st);
  }
  EXPECT_GT(stats[0].moves, 1000);
  EXPECT_EQ(stats[1].moves, stats[0].moves);
  EXPECT_EQ(meshes[1].faces, meshes[0].faces);
  EXPECT_TRUE(meshes[1].vertices == meshes[0].vertices);
}

TEST(PointFitting, StopsWhenCancelledMidwayOnSeveralThreads) {
  // A ball of about 80k vertices fitted on 4 threads (the calling thread's share takes about
  // 0.1 s of its CPU time), cancelled after 5 ms of it (between phases or inside one, where
  // the calling thread polls every 4096 vertices): every move is undone and the mesh is its
  // clean input again.
  UnrepairedSurfaceNets nets = SurfaceNetsBeforeRepair(BallGrid(144, 64.6));
  ASSERT_GT(nets.mesh.vertices.size(), 60000u);
  const TriangleMesh input = nets.mesh;
  FitOptions options;
  options.threads = 4;
  CancelToken cancel;
  const CancelAfterThreadCpu canceller(cancel, 0.005);
  const absl::StatusOr<FitStats> stats = FitToPoints(nets.mesh, 1.0, {}, options, cancel);
  EXPECT_EQ(stats.status().code(), absl::StatusCode::kCancelled);
  EXPECT_GE(canceller.cancelled_at(), 0);
  EXPECT_TRUE(nets.mesh.vertices == input.vertices);
}

// Its speed is measured in tests/bench; here, that a 150k-point ball gives a clean surface.
TEST(PointFitting, SmoothSurfaceOfA200CubedBallWith150kPointsIsClean) {
  const double l = 1.0, radius = 92;
  const std::array<double, 3> centre = {100.3, 99.8, 100.1};
  const std::vector<Point3f> points = SpherePoints(150000, centre, radius, 11);
  const VoxelGrid g = SampledSphereGrid(200, l, centre, radius, points);
  absl::StatusOr<TriangleMesh> mesh = SmoothSurface(g, points);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  const MeshReport r = CheckMesh(*mesh);
  EXPECT_TRUE(r.closed && r.manifold && r.oriented && r.positive_volume);
  EXPECT_EQ(r.self_intersections, 0);
  EXPECT_EQ(r.shells, 1);
}

}  // namespace
}  // namespace membrane
