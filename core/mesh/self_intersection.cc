#include "core/mesh/self_intersection.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/mesh/triangle_intersection.h"

namespace membrane {
namespace {

struct Box {
  std::array<float, 3> lo, hi;
};

bool Overlap(const Box& a, const Box& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

bool ValidFace(const std::array<int32_t, 3>& f, int64_t nv) {
  for (int32_t i : f)
    if (i < 0 || i >= nv) return false;
  return true;
}

using CellCoord = std::array<int32_t, 3>;

// A spatial hash of cells of side `cell` over the faces' boxes: each (face, cell touched by its
// box) entry goes to bucket hash(cell) mod B, stored as compressed rows. Only occupied cells
// cost memory, so a thin surface in a big box is as cheap as a compact one.
class FaceHash {
 public:
  FaceHash(const std::vector<Box>& boxes, const std::vector<int32_t>& faces) {
    Box all = boxes[faces[0]];
    double extent_sum = 0;
    for (int32_t f : faces) {
      const Box& b = boxes[f];
      double e = 0;
      for (int k = 0; k < 3; ++k) {
        all.lo[k] = std::min(all.lo[k], b.lo[k]);
        all.hi[k] = std::max(all.hi[k], b.hi[k]);
        e = std::max(e, static_cast<double>(b.hi[k]) - b.lo[k]);
      }
      extent_sum += e;
    }
    double diag = 0;
    for (int k = 0; k < 3; ++k) {
      lo_[k] = all.lo[k];
      diag = std::max(diag, static_cast<double>(all.hi[k]) - all.lo[k]);
    }
    // Cells about the size of a face; coarser when the entry count would not stay linear in
    // the face count (a few huge faces), and never more than 2^20 per axis.
    cell_ = std::max({extent_sum / faces.size(), diag / (1 << 20), 1e-30});
    const double max_entries = 16.0 * faces.size() + 64;
    for (;;) {
      double entries = 0;
      for (int32_t f : faces) {
        double n = 1;
        for (int k = 0; k < 3; ++k) n *= Cell(boxes[f].hi[k], k) - Cell(boxes[f].lo[k], k) + 1;
        entries += n;
        if (entries > max_entries) break;
      }
      if (entries <= max_entries) {
        num_entries_ = static_cast<int64_t>(entries);
        break;
      }
      cell_ *= 1.5;
    }
    num_buckets_ = static_cast<uint64_t>(num_entries_) + 1;
    start_.assign(num_buckets_ + 1, 0);
    ForEachEntry(boxes, faces, [&](int32_t, const CellCoord& c) { ++start_[Bucket(c) + 1]; });
    for (uint64_t b = 0; b < num_buckets_; ++b) start_[b + 1] += start_[b];
    face_.resize(num_entries_);
    cell_of_.resize(num_entries_);
    std::vector<int64_t> fill(start_.begin(), start_.end() - 1);
    ForEachEntry(boxes, faces, [&](int32_t f, const CellCoord& c) {
      const int64_t e = fill[Bucket(c)]++;
      face_[e] = f;
      cell_of_[e] = c;
    });
  }

  int32_t Cell(float v, int axis) const {
    return static_cast<int32_t>(std::floor((v - lo_[axis]) / cell_));
  }
  uint64_t num_buckets() const { return num_buckets_; }
  int64_t begin(uint64_t b) const { return start_[b]; }
  int64_t end(uint64_t b) const { return start_[b + 1]; }
  int32_t face(int64_t e) const { return face_[e]; }
  const CellCoord& cell(int64_t e) const { return cell_of_[e]; }

 private:
  uint64_t Bucket(const CellCoord& c) const {
    const uint64_t h = static_cast<uint64_t>(static_cast<uint32_t>(c[0])) * 73856093u ^
                       static_cast<uint64_t>(static_cast<uint32_t>(c[1])) * 19349663u ^
                       static_cast<uint64_t>(static_cast<uint32_t>(c[2])) * 83492791u;
    return h % num_buckets_;
  }
  template <typename Fn>
  void ForEachEntry(const std::vector<Box>& boxes, const std::vector<int32_t>& faces, Fn fn) const {
    for (int32_t f : faces) {
      const Box& b = boxes[f];
      const CellCoord lo{Cell(b.lo[0], 0), Cell(b.lo[1], 1), Cell(b.lo[2], 2)};
      const CellCoord hi{Cell(b.hi[0], 0), Cell(b.hi[1], 1), Cell(b.hi[2], 2)};
      for (int32_t z = lo[2]; z <= hi[2]; ++z)
        for (int32_t y = lo[1]; y <= hi[1]; ++y)
          for (int32_t x = lo[0]; x <= hi[0]; ++x) fn(f, CellCoord{x, y, z});
    }
  }

  std::array<double, 3> lo_{0, 0, 0};
  double cell_ = 1;
  int64_t num_entries_ = 0;
  uint64_t num_buckets_ = 1;
  std::vector<int64_t> start_;
  std::vector<int32_t> face_;
  std::vector<CellCoord> cell_of_;
};

}  // namespace

std::vector<std::pair<int32_t, int32_t>> FindIntersectingFaces(const TriangleMesh& mesh) {
  const int64_t nv = static_cast<int64_t>(mesh.vertices.size());
  const int32_t nf = static_cast<int32_t>(mesh.faces.size());
  std::vector<Box> boxes(nf);
  std::vector<int32_t> faces;
  faces.reserve(nf);
  for (int32_t f = 0; f < nf; ++f) {
    if (!ValidFace(mesh.faces[f], nv)) continue;
    Box b;
    b.lo = b.hi = mesh.vertices[mesh.faces[f][0]];
    for (int k = 1; k < 3; ++k) {
      const Point3f& p = mesh.vertices[mesh.faces[f][k]];
      for (int a = 0; a < 3; ++a) {
        b.lo[a] = std::min(b.lo[a], p[a]);
        b.hi[a] = std::max(b.hi[a], p[a]);
      }
    }
    boxes[f] = b;
    faces.push_back(f);
  }
  std::vector<std::pair<int32_t, int32_t>> pairs;
  if (faces.empty()) return pairs;
  const FaceHash hash(boxes, faces);
  // Lowest cell of each face's box: the lowest cell of two boxes' overlap is the per-axis
  // maximum of theirs, so each pair is tested once, in that cell.
  std::vector<CellCoord> low_cell(nf);
  for (int32_t f : faces)
    for (int k = 0; k < 3; ++k) low_cell[f][k] = hash.Cell(boxes[f].lo[k], k);
  auto triangle = [&](int32_t f) {
    const auto& idx = mesh.faces[f];
    return Triangle3d{ToVec3d(mesh.vertices[idx[0]]), ToVec3d(mesh.vertices[idx[1]]),
                      ToVec3d(mesh.vertices[idx[2]])};
  };
  for (uint64_t b = 0; b < hash.num_buckets(); ++b) {
    for (int64_t i = hash.begin(b); i < hash.end(b); ++i) {
      const int32_t fi = hash.face(i);
      const CellCoord& c = hash.cell(i);
      const CellCoord& li = low_cell[fi];
      for (int64_t j = i + 1; j < hash.end(b); ++j) {
        if (hash.cell(j) != c) continue;  // another cell in the same bucket
        const int32_t fj = hash.face(j);
        const CellCoord& lj = low_cell[fj];
        if (std::max(li[0], lj[0]) != c[0] || std::max(li[1], lj[1]) != c[1] ||
            std::max(li[2], lj[2]) != c[2])
          continue;
        if (!Overlap(boxes[fi], boxes[fj])) continue;
        if (MeshTrianglesIntersect(mesh.faces[fi], triangle(fi), mesh.faces[fj], triangle(fj)))
          pairs.emplace_back(std::min(fi, fj), std::max(fi, fj));
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace membrane
