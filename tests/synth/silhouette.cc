#include "tests/synth/silhouette.h"

#include <cmath>
#include <utility>

namespace membrane::testing {

Silhouette::Silhouette(const Vec3d& direction, double half_width, double pixel)
    : half_width_(half_width), pixel_(pixel), n_(static_cast<int>(std::ceil(2 * half_width / pixel))) {
  // Any vector not parallel to the direction seeds the basis.
  const Vec3d seed = std::abs(direction[0]) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
  u_ = Normalized(Cross(direction, seed));
  v_ = Cross(direction, u_);
  occupied_.assign(static_cast<size_t>(n_) * n_, 0);
}

void Silhouette::Add(const Point3f& p) {
  const Vec3d q = {p[0], p[1], p[2]};
  const int i = static_cast<int>(std::floor((Dot(q, u_) + half_width_) / pixel_));
  const int j = static_cast<int>(std::floor((Dot(q, v_) + half_width_) / pixel_));
  if (i < 0 || j < 0 || i >= n_ || j >= n_) return;
  occupied_[static_cast<size_t>(j) * n_ + i] = 1;
}

int Silhouette::EnclosedEmptyPixels() const {
  std::vector<char> outside(occupied_.size(), 0);
  std::vector<std::pair<int, int>> stack;
  const auto visit = [&](int i, int j) {
    if (i < 0 || j < 0 || i >= n_ || j >= n_) return;
    const size_t k = static_cast<size_t>(j) * n_ + i;
    if (occupied_[k] || outside[k]) return;
    outside[k] = 1;
    stack.emplace_back(i, j);
  };
  for (int t = 0; t < n_; ++t) {
    visit(t, 0), visit(t, n_ - 1), visit(0, t), visit(n_ - 1, t);
  }
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    visit(i + 1, j), visit(i - 1, j), visit(i, j + 1), visit(i, j - 1);
  }
  int enclosed = 0;
  for (size_t k = 0; k < occupied_.size(); ++k) enclosed += !occupied_[k] && !outside[k];
  return enclosed;
}

bool Silhouette::Overlaps(const Silhouette& other) const {
  for (size_t k = 0; k < occupied_.size() && k < other.occupied_.size(); ++k)
    if (occupied_[k] && other.occupied_[k]) return true;
  return false;
}

}  // namespace membrane::testing
