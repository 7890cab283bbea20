#include "core/mesh/mesh_decimation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/types/span.h"
#include "core/geometry/vec3.h"
#include "core/mesh/collapse_queue.h"
#include "core/mesh/error_quadric.h"
#include "core/mesh/face_grid.h"
#include "core/mesh/fan_embedding.h"
#include "core/mesh/triangle_intersection.h"

namespace membrane {
namespace {

// A moved face may turn by at most acos(0.2), 78 degrees: beyond that the quadric, which
// measures distances to planes, no longer says how far the surface moved.
constexpr double kMinCosine = 0.2;
// A moved face may become thinner than this quality (1 for an equilateral triangle) only if it
// was already thinner; below kDegenerateQuality never (the check's exact predicates would
// call it degenerate, or nearly so).
constexpr double kThinQuality = 0.02;
constexpr double kDegenerateQuality = 1e-6;
// A small term in the squared edge length squared (the units of an area-weighted quadric) so
// that on flat parts, where every collapse costs 0, short edges go first and the faces stay
// even.
constexpr double kLengthWeight = 1e-4;
constexpr int kCancelPeriod = 4096;
constexpr size_t kMaxFan = 64;
constexpr FaceBox kEmptyBox{{HUGE_VALF, HUGE_VALF, HUGE_VALF}, {-HUGE_VALF, -HUGE_VALF, -HUGE_VALF}};

// 1 for an equilateral triangle, 0 for a degenerate one: 2 sqrt(3) |n| / (sum of squared
// edges), with n twice the area vector.
double Quality(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const double edges = SquaredNorm(b - a) + SquaredNorm(c - b) + SquaredNorm(a - c);
  if (!(edges > 0)) return 0;
  return 2 * std::sqrt(3.0) * Norm(TriangleNormal(a, b, c)) / edges;
}

// Shells of a closed manifold mesh and their genus, from V - E + F = 2 - 2 g with E = 3 F / 2.
std::vector<int> ShellGenera(const TriangleMesh& mesh) {
  const int32_t nv = static_cast<int32_t>(mesh.vertices.size());
  std::vector<int32_t> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& f : mesh.faces)
    for (int k = 1; k < 3; ++k) {
      const int32_t x = find(f[0]), y = find(f[k]);
      if (x != y) parent[std::max(x, y)] = std::min(x, y);
    }
  std::vector<int64_t> faces(nv, 0), vertices(nv, 0);
  std::vector<char> used(nv, 0);
  for (const auto& f : mesh.faces) {
    ++faces[find(f[0])];
    for (int32_t v : f) used[v] = 1;
  }
  for (int32_t v = 0; v < nv; ++v)
    if (used[v]) ++vertices[find(v)];
  std::vector<int> genera;
  for (int32_t v = 0; v < nv; ++v) {
    if (!used[v] || find(v) != v) continue;
    const int64_t euler = vertices[v] - faces[v] / 2;
    genera.push_back(static_cast<int>((2 - euler) / 2));
  }
  return genera;
}

class Decimator {
 public:
  Decimator(TriangleMesh& mesh, const DecimationOptions& options, const CancelToken& cancel,
            ProgressRange progress)
      : mesh_(mesh), options_(options), cancel_(cancel), progress_(progress) {}

  // Builds the vertex-face lists; FailedPrecondition unless the mesh is closed, oriented and
  // manifold.
  absl::Status Prepare();
  absl::Status Run(DecimationStats& stats);

 private:
  absl::Span<const int32_t> FacesOf(int32_t v) const {
    return absl::MakeConstSpan(refs_.data() + start_[v], count_[v]);
  }
  void BuildFaceLists();
  void BuildGrid();
  void FillQueue();
  // The collapse point of edge (u, w), on the grid, and its cost.
  double Place(int32_t u, int32_t w, Vec3d& point) const;
  void Push(int32_t u, int32_t w);
  bool TryCollapse(int32_t a, int32_t b);
  // True when a moved face (the scratch below) would meet another face or a fellow.
  bool MovedFacesCross(int32_t a, int32_t b, const Vec3d& point);
  void Compact();

  TriangleMesh& mesh_;
  const DecimationOptions& options_;
  const CancelToken& cancel_;
  const ProgressRange progress_;

  std::vector<char> face_alive_;
  int64_t alive_faces_ = 0;
  std::vector<ErrorQuadric> quadric_;
  std::vector<uint32_t> stamp_;  // bumped whenever a vertex moves or dies
  std::vector<int64_t> start_;
  std::vector<int32_t> count_;
  std::vector<int32_t> refs_;  // per vertex, its live faces: refs_[start_[v], + count_[v])
  std::vector<uint32_t> vertex_mark_;
  uint32_t vertex_mark_id_ = 0;
  std::vector<uint32_t> face_mark_;
  uint32_t face_mark_id_ = 0;
  // Each face's box, empty (lo > hi) once it is removed: the crossing test's broad phase reads
  // one record per candidate.
  std::vector<FaceBox> face_box_;
  CollapseQueue queue_;
  FaceGrid grid_{1.0};
  int64_t grid_faces_ = 0;    // live faces when the grid was built
  int64_t grid_entries_ = 0;  // its entries then

  // Scratch of one collapse: the faces it moves, their new corners and positions.
  std::vector<int32_t> moved_;
  std::vector<std::array<int32_t, 3>> moved_corners_;
  std::vector<Triangle3d> moved_triangles_;
  std::vector<FaceBox> moved_boxes_;
  std::vector<FacePlane> moved_planes_;
  std::vector<Vec3d> ring_;
  std::vector<uint64_t> cells_;
};

void Decimator::BuildFaceLists() {
  const int32_t nv = static_cast<int32_t>(mesh_.vertices.size());
  const int32_t nf = static_cast<int32_t>(mesh_.faces.size());
  start_.assign(nv + 1, 0);
  count_.assign(nv, 0);
  for (int32_t f = 0; f < nf; ++f)
    if (face_alive_[f])
      for (int32_t v : mesh_.faces[f]) ++count_[v];
  for (int32_t v = 0; v < nv; ++v) start_[v + 1] = start_[v] + count_[v];
  refs_.assign(start_[nv], 0);
  std::vector<int32_t> fill(nv, 0);
  for (int32_t f = 0; f < nf; ++f)
    if (face_alive_[f])
      for (int32_t v : mesh_.faces[f]) refs_[start_[v] + fill[v]++] = f;
}

absl::Status Decimator::Prepare() {
  const int32_t nv = static_cast<int32_t>(mesh_.vertices.size());
  const int32_t nf = static_cast<int32_t>(mesh_.faces.size());
  for (int32_t f = 0; f < nf; ++f)
    for (int32_t v : mesh_.faces[f])
      if (v < 0 || v >= nv) {
        return absl::FailedPreconditionError(
            absl::StrCat("face ", f, " has vertex index ", v, " outside [0, ", nv, ")"));
      }
  face_alive_.assign(nf, 1);
  alive_faces_ = nf;
  BuildFaceLists();
  // Around each vertex v, face (v, x, y) steps from x to y: a closed oriented manifold's
  // steps form one cycle through all of v's neighbours, each entered and left once.
  std::vector<std::pair<int32_t, int32_t>> steps;
  for (int32_t v = 0; v < nv; ++v) {
    if (count_[v] == 0) continue;
    steps.clear();
    for (int32_t f : FacesOf(v)) {
      const auto& c = mesh_.faces[f];
      const int k = c[0] == v ? 0 : c[1] == v ? 1 : 2;
      steps.push_back({c[(k + 1) % 3], c[(k + 2) % 3]});
    }
    bool fan = steps.size() >= 3;
    int32_t at = steps[0].second;
    size_t walked = 1;
    while (fan && at != steps[0].first) {
      int found = -1;
      for (size_t i = 0; i < steps.size(); ++i)
        if (steps[i].first == at) {
          if (found >= 0) fan = false;
          found = static_cast<int>(i);
        }
      if (found < 0 || ++walked > steps.size()) fan = false;
      if (fan) at = steps[found].second;
    }
    if (!fan || walked != steps.size()) {
      return absl::FailedPreconditionError(absl::StrCat(
          "vertex ", v, "'s ", steps.size(),
          " faces do not form one oriented fan: the mesh is not closed, oriented and manifold"));
    }
  }
  return absl::OkStatus();
}

void Decimator::BuildGrid() {
  // Cells of three times the mean edge (twice, four times and once cost 1.1x, 1.0x and 1.7x
  // the CPU time on a 150k-face torus): a face is entered in one to eight of them.
  double sum = 0;
  int64_t n = 0;
  const int32_t nf = static_cast<int32_t>(mesh_.faces.size());
  for (int32_t f = 0; f < nf; ++f) {
    if (!face_alive_[f]) continue;
    const auto& c = mesh_.faces[f];
    sum += Norm(ToVec3d(mesh_.vertices[c[1]]) - ToVec3d(mesh_.vertices[c[0]]));
    ++n;
  }
  const double cell = n > 0 && sum > 0 ? 3 * sum / n : 1.0;
  grid_ = FaceGrid(cell);
  for (int32_t f = 0; f < nf; ++f)
    if (face_alive_[f]) grid_.Insert(f, face_box_[f]);
  grid_faces_ = alive_faces_;
  grid_entries_ = grid_.entries();
}

double Decimator::Place(int32_t u, int32_t w, Vec3d& point) const {
  const ErrorQuadric q = quadric_[u] + quadric_[w];
  const Vec3d pu = ToVec3d(mesh_.vertices[u]), pw = ToVec3d(mesh_.vertices[w]);
  const Vec3d mid = 0.5 * (pu + pw);
  const double length2 = SquaredNorm(pw - pu);
  const double regular = kLengthWeight * length2 * length2;
  auto on_grid = [&](const Vec3d& p) { return ToVec3d(options_.grid.Snap(ToPoint3f(p))); };
  // The quadric's own minimum, unless it lies further than an edge from the edge's middle
  // (nearly parallel planes put it far away, and the collapse would then be refused anyway).
  Vec3d best;
  if (q.Minimizer(best) && SquaredNorm(best - mid) <= length2) {
    point = on_grid(best);
    return q.Evaluate(point) + regular;
  }
  double best_cost = 0;
  bool any = false;
  for (const Vec3d& candidate : {mid, pu, pw}) {
    const Vec3d p = on_grid(candidate);
    const double cost = q.Evaluate(p);
    if (!any || cost < best_cost) {
      any = true;
      best_cost = cost;
      point = p;
    }
  }
  return best_cost + regular;
}

void Decimator::Push(int32_t u, int32_t w) {
  if (u > w) std::swap(u, w);
  Vec3d point;
  const double cost = Place(u, w, point);
  queue_.Push({static_cast<float>(cost), u, w, stamp_[u], stamp_[w]});
}

void Decimator::FillQueue() {
  queue_.Clear();
  // Every edge once: in a closed oriented mesh, (x, y) runs from the lower index in exactly
  // one of its two faces. Pushed in reverse face order, so that among equal costs (a bucket
  // gives back its last entry first) the first faces' edges come first.
  const int32_t nf = static_cast<int32_t>(mesh_.faces.size());
  for (int32_t f = nf - 1; f >= 0; --f) {
    if (!face_alive_[f]) continue;
    const auto& c = mesh_.faces[f];
    for (int k = 2; k >= 0; --k) {
      const int32_t u = c[k], w = c[(k + 1) % 3];
      if (u < w) Push(u, w);
    }
  }
}

bool Decimator::MovedFacesCross(int32_t a, int32_t b, const Vec3d& point) {
  const size_t n = moved_.size();
  // Among themselves: all share the new vertex; a fan proven embedded needs no pair tests.
  ring_.clear();
  {
    // The ring in fan order: each moved face is (a, x, y) up to rotation, stepping x to y.
    std::vector<std::pair<int32_t, int32_t>> steps;
    steps.reserve(n);
    for (const auto& c : moved_corners_) {
      const int k = c[0] == a ? 0 : c[1] == a ? 1 : 2;
      steps.push_back({c[(k + 1) % 3], c[(k + 2) % 3]});
    }
    int32_t at = steps[0].first;
    for (size_t i = 0; i < n; ++i) {
      ring_.push_back(ToVec3d(mesh_.vertices[at]));
      int32_t next = -1;
      for (const auto& s : steps)
        if (s.first == at) next = s.second;
      if (next < 0) return true;  // not one fan: cannot happen after the link condition
      at = next;
    }
  }
  if (!FanIsEmbedded(point, ring_)) {
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i + 1; j < n; ++j)
        if (MeshTrianglesIntersect(moved_corners_[i], moved_triangles_[i], moved_corners_[j],
                                   moved_triangles_[j])) {
          return true;
        }
  }
  // Against every other face near them. The faces the collapse removes or moves are not
  // candidates: the removed ones go, the moved ones were just tested.
  FaceBox all = moved_boxes_[0];
  for (const FaceBox& box : moved_boxes_)
    for (int k = 0; k < 3; ++k) {
      all.lo[k] = std::min(all.lo[k], box.lo[k]);
      all.hi[k] = std::max(all.hi[k], box.hi[k]);
    }
  const uint32_t id = ++face_mark_id_;
  for (int32_t f : FacesOf(a)) face_mark_[f] = id;
  for (int32_t f : FacesOf(b)) face_mark_[f] = id;
  moved_planes_.clear();
  for (const Triangle3d& t : moved_triangles_) moved_planes_.push_back(MakeFacePlane(t));
  bool crossing = false;
  grid_.ForEachCandidateOf(moved_boxes_, all, cells_, [&](int32_t f) {
    // Removed faces have empty boxes; a face met again, or one the collapse moves, is marked;
    // a stale entry of a face that moved away fails the test on its current box.
    const FaceBox& box = face_box_[f];
    if (crossing || face_mark_[f] == id || !BoxesOverlap(box, all)) return;
    face_mark_[f] = id;
    const auto& c = mesh_.faces[f];
    Triangle3d t;
    bool have_plane = false;
    FacePlane plane;
    for (size_t i = 0; i < n && !crossing; ++i) {
      if (!BoxesOverlap(box, moved_boxes_[i])) continue;
      if (!have_plane) {
        t = {ToVec3d(mesh_.vertices[c[0]]), ToVec3d(mesh_.vertices[c[1]]),
             ToVec3d(mesh_.vertices[c[2]])};
        plane = MakeFacePlane(t);
        have_plane = true;
      }
      crossing = MeshTrianglesIntersect(moved_corners_[i], moved_triangles_[i], moved_planes_[i],
                                        c, t, plane);
    }
  });
  return crossing;
}

bool Decimator::TryCollapse(int32_t a, int32_t b) {
  const absl::Span<const int32_t> faces_a = FacesOf(a), faces_b = FacesOf(b);
  if (faces_a.size() + faces_b.size() > kMaxFan + 2) return false;
  // The edge's two faces and the vertices opposite it.
  int32_t shared[2];
  int n_shared = 0;
  for (int32_t f : faces_a) {
    const auto& c = mesh_.faces[f];
    if (c[0] != b && c[1] != b && c[2] != b) continue;
    if (n_shared == 2) return false;
    shared[n_shared++] = f;
  }
  if (n_shared != 2) return false;
  int32_t opposite[2];
  for (int s = 0; s < 2; ++s)
    for (int32_t v : mesh_.faces[shared[s]])
      if (v != a && v != b) opposite[s] = v;
  if (opposite[0] == opposite[1]) return false;
  // A tetrahedron would collapse to two faces back to back.
  if (count_[opposite[0]] <= 3 || count_[opposite[1]] <= 3) return false;
  // The link condition: no neighbour common to a and b but the two opposite vertices.
  const uint32_t mark = ++vertex_mark_id_;
  for (int32_t f : faces_a)
    for (int32_t v : mesh_.faces[f]) vertex_mark_[v] = mark;
  for (int32_t f : faces_b)
    for (int32_t v : mesh_.faces[f])
      if (v != a && v != b && v != opposite[0] && v != opposite[1] && vertex_mark_[v] == mark) {
        return false;
      }

  Vec3d point;
  Place(a, b, point);
  // The faces that move, with b renamed a and a at `point`: none may turn over or thin out.
  moved_.clear();
  moved_corners_.clear();
  moved_triangles_.clear();
  moved_boxes_.clear();
  for (const absl::Span<const int32_t> list : {faces_a, faces_b})
    for (int32_t f : list) {
      if (f == shared[0] || f == shared[1]) continue;
      std::array<int32_t, 3> c = mesh_.faces[f];
      Triangle3d before, after;
      for (int k = 0; k < 3; ++k) {
        before[k] = ToVec3d(mesh_.vertices[c[k]]);
        if (c[k] == b) c[k] = a;
        after[k] = c[k] == a ? point : before[k];
      }
      const Vec3d n0 = TriangleNormal(before[0], before[1], before[2]);
      const Vec3d n1 = TriangleNormal(after[0], after[1], after[2]);
      if (!(Dot(n0, n1) > kMinCosine * Norm(n0) * Norm(n1))) return false;
      const double q1 = Quality(after[0], after[1], after[2]);
      if (q1 < kDegenerateQuality) return false;
      if (q1 < kThinQuality && q1 < Quality(before[0], before[1], before[2])) return false;
      FaceBox box;
      box.lo = box.hi = ToPoint3f(after[0]);
      for (int k = 1; k < 3; ++k)
        for (int x = 0; x < 3; ++x) {
          box.lo[x] = std::min(box.lo[x], static_cast<float>(after[k][x]));
          box.hi[x] = std::max(box.hi[x], static_cast<float>(after[k][x]));
        }
      moved_.push_back(f);
      moved_corners_.push_back(c);
      moved_triangles_.push_back(after);
      moved_boxes_.push_back(box);
    }
  if (moved_.size() < 3 || MovedFacesCross(a, b, point)) return false;

  // Commit: the two faces go, b's faces become a's, a moves to `point`.
  for (int32_t f : shared) {
    face_alive_[f] = 0;
    face_box_[f] = kEmptyBox;
  }
  alive_faces_ -= 2;
  for (int32_t f : faces_b)
    for (int32_t& v : mesh_.faces[f])
      if (v == b) v = a;
  mesh_.vertices[a] = ToPoint3f(point);
  quadric_[a] += quadric_[b];
  ++stamp_[a];
  ++stamp_[b];
  const int64_t start = static_cast<int64_t>(refs_.size());
  refs_.insert(refs_.end(), moved_.begin(), moved_.end());
  start_[a] = start;
  count_[a] = static_cast<int32_t>(moved_.size());
  count_[b] = 0;
  for (int32_t o : opposite) {
    int32_t* list = refs_.data() + start_[o];
    count_[o] = static_cast<int32_t>(
        std::remove_if(list, list + count_[o], [&](int32_t f) { return !face_alive_[f]; }) -
        list);
  }
  for (size_t i = 0; i < moved_.size(); ++i) {
    face_box_[moved_[i]] = moved_boxes_[i];
    grid_.Insert(moved_[i], moved_boxes_[i]);
  }
  const uint32_t ring_mark = ++vertex_mark_id_;
  for (const auto& c : moved_corners_)
    for (int32_t v : c)
      if (v != a && vertex_mark_[v] != ring_mark) {
        vertex_mark_[v] = ring_mark;
        Push(a, v);
      }
  return true;
}

void Decimator::Compact() {
  const int32_t nv = static_cast<int32_t>(mesh_.vertices.size());
  std::vector<int32_t> new_index(nv, -1);
  std::vector<std::array<int32_t, 3>> faces;
  faces.reserve(alive_faces_);
  for (size_t f = 0; f < mesh_.faces.size(); ++f)
    if (face_alive_[f]) {
      faces.push_back(mesh_.faces[f]);
      for (int32_t v : mesh_.faces[f]) new_index[v] = 0;
    }
  std::vector<Point3f> vertices;
  for (int32_t v = 0; v < nv; ++v)
    if (new_index[v] == 0) {
      new_index[v] = static_cast<int32_t>(vertices.size());
      vertices.push_back(mesh_.vertices[v]);
    }
  for (auto& c : faces)
    for (int32_t& v : c) v = new_index[v];
  mesh_.faces = std::move(faces);
  mesh_.vertices = std::move(vertices);
}

absl::Status Decimator::Run(DecimationStats& stats) {
  const int32_t nv = static_cast<int32_t>(mesh_.vertices.size());
  quadric_.assign(nv, ErrorQuadric{});
  for (const auto& c : mesh_.faces) {
    const Vec3d p0 = ToVec3d(mesh_.vertices[c[0]]);
    const Vec3d n = TriangleNormal(p0, ToVec3d(mesh_.vertices[c[1]]),
                                   ToVec3d(mesh_.vertices[c[2]]));
    const double twice_area = Norm(n);
    if (!(twice_area > 0)) continue;
    const ErrorQuadric q = ErrorQuadric::Plane((1 / twice_area) * n, p0, twice_area / 2);
    for (int32_t v : c) quadric_[v] += q;
  }
  stamp_.assign(nv, 0);
  vertex_mark_.assign(nv, 0);
  face_mark_.assign(mesh_.faces.size(), 0);
  face_box_.resize(mesh_.faces.size());
  for (size_t f = 0; f < mesh_.faces.size(); ++f)
    face_box_[f] = BoxOfFace(mesh_, static_cast<int32_t>(f));
  BuildGrid();
  FillQueue();
  stats.passes = 1;
  int64_t pass_collapses = 0;
  int64_t since_poll = 0;
  absl::Status status;
  progress_.Begin(alive_faces_ - options_.target_faces);
  int64_t faces_told = alive_faces_;
  while (alive_faces_ > options_.target_faces) {
    if (++since_poll == kCancelPeriod) {
      since_poll = 0;
      progress_.Add(faces_told - alive_faces_);
      faces_told = alive_faces_;
      if (cancel_.cancelled()) {
        status = absl::CancelledError("decimation cancelled");
        break;
      }
    }
    if (queue_.empty()) {
      if (pass_collapses == 0) break;
      pass_collapses = 0;
      ++stats.passes;
      FillQueue();
      continue;
    }
    const CollapseCandidate e = queue_.Pop();
    if (stamp_[e.a] != e.stamp_a || stamp_[e.b] != e.stamp_b || count_[e.a] == 0 ||
        count_[e.b] == 0) {
      continue;
    }
    if (!TryCollapse(e.a, e.b)) {
      ++stats.refused;
      continue;
    }
    ++stats.collapses;
    ++pass_collapses;
    // Faces have grown: coarser cells. Stale entries have piled up (every collapse enters the
    // faces it moves again): fresh cells, which halves what a search reads.
    if (2 * alive_faces_ < grid_faces_ || grid_.entries() > 2 * grid_entries_) BuildGrid();
    // The lists have grown: pack them.
    if (static_cast<int64_t>(refs_.size()) > 6 * alive_faces_ + 4096) BuildFaceLists();
  }
  progress_.Add(faces_told - alive_faces_);
  queue_.Clear();
  grid_ = FaceGrid(1.0);
  face_box_ = {};
  face_mark_ = {};
  Compact();
  stats.faces_after = static_cast<int64_t>(mesh_.faces.size());
  stats.vertices_after = static_cast<int64_t>(mesh_.vertices.size());
  return status;
}

}  // namespace

int64_t MinimumFacesOfGenus(int genus) {
  const int64_t g = std::max(genus, 0);
  int64_t vertices = static_cast<int64_t>(std::ceil((7 + std::sqrt(1.0 + 48.0 * g)) / 2));
  if (g == 2) vertices = 10;
  return 2 * vertices - 4 + 4 * g;
}

absl::StatusOr<DecimationStats> DecimateMesh(TriangleMesh& mesh, const DecimationOptions& options,
                                             const CancelToken& cancel, ProgressRange progress) {
  DecimationStats stats;
  stats.target_faces = options.target_faces;
  stats.faces_before = stats.faces_after = static_cast<int64_t>(mesh.faces.size());
  stats.vertices_before = stats.vertices_after = static_cast<int64_t>(mesh.vertices.size());
  if (options.target_faces < kMinTargetFaces) {
    return absl::InvalidArgumentError(absl::StrCat("target of ", options.target_faces,
                                                   " faces: it must be at least ",
                                                   kMinTargetFaces, " (a tetrahedron)"));
  }
  Decimator decimator(mesh, options, cancel, progress);
  if (absl::Status s = decimator.Prepare(); !s.ok()) return s;
  const std::vector<int> genera = ShellGenera(mesh);
  int64_t fewest = 0;
  for (int g : genera) fewest += MinimumFacesOfGenus(g);
  if (options.target_faces < fewest) {
    return absl::InvalidArgumentError(absl::StrCat(
        "target of ", options.target_faces, " faces is below the ", fewest,
        " faces that the surface's ", genera.size(), genera.size() == 1 ? " shell" : " shells",
        " of genus ", absl::StrJoin(genera, ", "), " need at the least; ask for ", fewest,
        " or more"));
  }
  if (stats.faces_before <= options.target_faces) return stats;
  if (absl::Status s = decimator.Run(stats); !s.ok()) return s;
  return stats;
}

}  // namespace membrane
