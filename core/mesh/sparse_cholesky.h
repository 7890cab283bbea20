// A sparse Cholesky factorization A = L L^T of a symmetric positive definite matrix, for the
// hole caps' thin plates solved to convergence (hole_caps.h): the discrete bi-Laplacian over a
// cap of a few thousand vertices takes Jacobi-preconditioned conjugate gradients hundreds to
// thousands of iterations (its condition number grows as the square of the vertex count), and
// the factor solves it exactly in a fraction of that time. Up-looking, row by row along the
// elimination tree, in a nested-dissection order from the unknowns' positions.
#ifndef MEMBRANE_CORE_MESH_SPARSE_CHOLESKY_H_
#define MEMBRANE_CORE_MESH_SPARSE_CHOLESKY_H_

#include <cstdint>
#include <optional>
#include <vector>

#include "absl/types/span.h"
#include "core/geometry/vec3.h"

namespace membrane {

// One entry of a symmetric matrix: both (row, col) and (col, row) are meant; repeated entries
// add up.
struct SymmetricEntry {
  int32_t row, col;
  double value;
};

class SparseCholesky {
 public:
  // Input: n unknowns, their positions (n of them: only the order of elimination depends on
  // them, nested dissection by coordinate bisection, which keeps the factor of a surface's
  // Laplacian-like matrix near O(n log n)), and the entries of A (indices in [0, n); each
  // off-diagonal pair given once, in either orientation, or split across both). nullopt when
  // A is not positive definite (a pivot <= 0 or not finite), an index is out of range, or the
  // factor would hold more than `max_entries` entries (checked before it is allocated).
  static std::optional<SparseCholesky> Factor(int32_t n, absl::Span<const Vec3d> positions,
                                              absl::Span<const SymmetricEntry> entries,
                                              int64_t max_entries);

  // Solves A x = b for each coordinate of b (n of them); returns x.
  std::vector<Vec3d> Solve(absl::Span<const Vec3d> b) const;

  // Entries of L (the diagonal included).
  int64_t entries() const { return static_cast<int64_t>(rows_.size()); }

 private:
  int32_t n_ = 0;
  std::vector<int32_t> order_;  // order_[k]: the unknown eliminated k-th
  // L by columns in the elimination order: column j's rows (the diagonal first) and values at
  // [start_[j], start_[j + 1]).
  std::vector<int64_t> start_;
  std::vector<int32_t> rows_;
  std::vector<double> values_;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_SPARSE_CHOLESKY_H_
