#include "core/mesh/angle_sectors.h"

#include <cmath>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

constexpr double kPi = std::numbers::pi;

int LibrarySector(double y, double x, int n) {
  return std::min(n - 1, static_cast<int>((std::atan2(y, x) + kPi) / (2 * kPi) * n));
}

// Random directions at several scales, the axes with both zeros, and directions on and
// within rounding of every boundary of each count.
std::vector<std::pair<double, double>> Directions(const std::vector<int>& counts) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  std::vector<std::pair<double, double>> directions;
  for (int i = 0; i < 600000; ++i) {
    const double scale = std::pow(10.0, i % 7 - 3);
    directions.emplace_back(scale * coordinate(rng), scale * coordinate(rng));
  }
  for (double x : {-2.0, -0.0, 0.0, 3.0})
    for (double y : {-5.0, -0.0, 0.0, 1.0}) directions.emplace_back(y, x);
  for (int n : counts)
    for (int k = 0; k <= n; ++k) {
      const double angle = -kPi + 2 * kPi * k / n;
      for (double nudge : {-1e-9, -1e-12, -1e-15, 0.0, 1e-15, 1e-12, 1e-9})
        for (double r : {1e-3, 1.0, 50.0})
          directions.emplace_back(r * std::sin(angle + nudge), r * std::cos(angle + nudge));
    }
  return directions;
}

TEST(AngleSectors, GiveTheLibrarysSectorEverywhere) {
  const std::vector<int> counts = {1, 2, 3, 5, 6, 12, 13, 24, 360};
  const std::vector<std::pair<double, double>> directions = Directions(counts);
  for (int n : counts) {
    const AngleSectors sectors(n);
    int mismatches = 0;
    for (const auto& [y, x] : directions) mismatches += sectors(y, x) != LibrarySector(y, x, n);
    EXPECT_EQ(mismatches, 0) << n << " sectors";
  }
}

}  // namespace
}  // namespace membrane
