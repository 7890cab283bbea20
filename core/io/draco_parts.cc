#include "core/io/draco_parts.h"

#include <algorithm>
#include <array>
#include <optional>
#include <utility>

#include "absl/strings/str_cat.h"
#include "core/base/parallel_tasks.h"
#include "core/io/geometry_checks.h"

namespace membrane {
namespace {

// Bins of the histogram the slabs are cut from: a slab's count is within a bin's points of
// its share.
constexpr int kSlabBins = 4096;

// The points dealt into at most `parts` slabs of nearly equal counts across the longest side
// of their box, in their order within each slab; empty slabs are left out.
std::vector<std::vector<Point3f>> DealIntoSlabs(const std::vector<Point3f>& points, int parts) {
  std::array<float, 3> low = points.front(), high = points.front();
  for (const Point3f& p : points)
    for (int c = 0; c < 3; ++c) {
      low[c] = std::min(low[c], p[c]);
      high[c] = std::max(high[c], p[c]);
    }
  int axis = 0;
  for (int c = 1; c < 3; ++c) {
    if (double{high[c]} - low[c] > double{high[axis]} - low[axis]) axis = c;
  }
  const double extent = double{high[axis]} - low[axis];
  const double scale = extent > 0 ? kSlabBins / extent : 0;
  const auto bin_of = [&](const Point3f& p) {
    return std::min(kSlabBins - 1, static_cast<int>((double{p[axis]} - low[axis]) * scale));
  };
  std::vector<size_t> bin_count(kSlabBins, 0);
  for (const Point3f& p : points) ++bin_count[bin_of(p)];
  // Slab s ends at the first bin whose running count reaches (s + 1) / parts of the points.
  std::vector<int> slab_of_bin(kSlabBins);
  std::vector<size_t> slab_count(parts, 0);
  size_t running = 0;
  int slab = 0;
  for (int b = 0; b < kSlabBins; ++b) {
    slab_of_bin[b] = slab;
    slab_count[slab] += bin_count[b];
    running += bin_count[b];
    if (slab + 1 < parts && running * parts >= (slab + 1) * points.size()) ++slab;
  }
  std::vector<std::vector<Point3f>> slabs(parts);
  for (int s = 0; s < parts; ++s) slabs[s].reserve(slab_count[s]);
  for (const Point3f& p : points) slabs[slab_of_bin[bin_of(p)]].push_back(p);
  std::erase_if(slabs, [](const std::vector<Point3f>& s) { return s.empty(); });
  return slabs;
}

absl::string_view GeometryName(DracoGeometry geometry) {
  return geometry == DracoGeometry::kMesh ? "mesh" : "point cloud";
}

// Where part `index` of `count` lies in the bytes, for messages.
std::string PartName(size_t index, size_t count, uint64_t begin, uint64_t size) {
  return absl::StrCat("part ", index + 1, " of ", count, " (bytes ", begin, "..", begin + size,
                      ")");
}

}  // namespace

absl::Status CheckDracoPartBytes(absl::Span<const uint64_t> part_bytes, uint64_t total_bytes) {
  if (part_bytes.empty()) return absl::OkStatus();
  if (part_bytes.size() > static_cast<size_t>(kMaxDracoParts)) {
    return absl::InvalidArgumentError(absl::StrCat("the upload has ", part_bytes.size(),
                                                   " parts, over the limit of ", kMaxDracoParts));
  }
  uint64_t sum = 0;
  for (size_t i = 0; i < part_bytes.size(); ++i) {
    if (part_bytes[i] == 0) {
      return absl::InvalidArgumentError(
          absl::StrCat("part ", i + 1, " of ", part_bytes.size(), " is empty (0 bytes)"));
    }
    // Each size is at most the total, checked before the sum takes it: no overflow.
    if (part_bytes[i] > total_bytes - sum) {
      return absl::InvalidArgumentError(absl::StrCat(
          "the parts' sizes pass the upload's ", total_bytes, " bytes at part ", i + 1, " of ",
          part_bytes.size(), " (", part_bytes[i], " bytes after ", sum, ")"));
    }
    sum += part_bytes[i];
  }
  if (sum != total_bytes) {
    return absl::InvalidArgumentError(absl::StrCat("the ", part_bytes.size(),
                                                   " parts' sizes sum to ", sum,
                                                   " bytes, not the upload's ", total_bytes));
  }
  return absl::OkStatus();
}

int DracoPartCount(size_t points) {
  return static_cast<int>(
      std::clamp<size_t>(points / kPointsPerDracoPart, 1, static_cast<size_t>(kMaxEncodedParts)));
}

absl::StatusOr<DracoParts> EncodeDracoPointCloudParts(std::vector<Point3f> points,
                                                      const DracoOptions& options, int parts,
                                                      int threads) {
  parts = std::clamp(parts, 1, kMaxDracoParts);
  if (parts > 1 && options.position_quantization_bits > 0 && !options.box) {
    // Draco would quantize each part over its own box: a point's position would depend on
    // its part.
    return absl::InvalidArgumentError(
        "a point cloud in parts needs lossless positions or an explicit quantization box");
  }
  std::vector<PointCloud> slabs;
  if (parts == 1 || points.size() < 2) {
    slabs.emplace_back().points = std::move(points);
  } else {
    // The slabs' bins need finite coordinates; the parts' encoders would refuse them anyway.
    if (absl::Status s = CheckFinitePoints(points, "cannot Draco-encode the point cloud");
        !s.ok()) {
      return s;
    }
    for (std::vector<Point3f>& slab : DealIntoSlabs(points, parts)) {
      slabs.emplace_back().points = std::move(slab);
    }
    points = std::vector<Point3f>();  // the slabs hold the points now
  }
  std::vector<std::optional<absl::StatusOr<DracoEncoding>>> encoded(slabs.size());
  RunTasks(threads, static_cast<int64_t>(slabs.size()), [&](int, int64_t t) {
    encoded[t] = EncodeDracoPointCloud(slabs[t], options);
    slabs[t].points = std::vector<Point3f>();
  });
  DracoParts result;
  size_t total = 0;
  for (const auto& e : encoded) {
    if (!e->ok()) return e->status();
    total += (*e)->bytes.size();
  }
  result.bytes.reserve(total);
  for (auto& e : encoded) {
    result.bytes += (*e)->bytes;
    result.part_bytes.push_back((*e)->bytes.size());
    result.max_position_error = std::max(result.max_position_error, (*e)->max_position_error);
    e.reset();
  }
  return result;
}

absl::StatusOr<std::vector<DecodedDracoCloud>> DecodeDracoParts(
    absl::string_view bytes, absl::Span<const uint64_t> part_bytes, DracoMeshPolicy policy,
    int threads) {
  std::vector<DecodedDracoCloud> parts;
  if (part_bytes.empty()) {
    absl::StatusOr<DecodedDracoCloud> one = DecodeDracoPointCloud(bytes, policy);
    if (!one.ok()) return one.status();
    parts.push_back(*std::move(one));
    return parts;
  }
  if (absl::Status s = CheckDracoPartBytes(part_bytes, bytes.size()); !s.ok()) return s;
  const size_t count = part_bytes.size();
  std::vector<uint64_t> begin(count, 0);
  for (size_t i = 1; i < count; ++i) begin[i] = begin[i - 1] + part_bytes[i - 1];
  std::vector<std::optional<absl::StatusOr<DecodedDracoCloud>>> decoded(count);
  RunTasks(threads, static_cast<int64_t>(count), [&](int, int64_t t) {
    decoded[t] = DecodeDracoPointCloud(bytes.substr(begin[t], part_bytes[t]), policy);
  });
  for (size_t i = 0; i < count; ++i) {
    const std::string name = PartName(i, count, begin[i], part_bytes[i]);
    const absl::StatusOr<DecodedDracoCloud>& part = *decoded[i];
    if (!part.ok()) {
      return absl::Status(part.status().code(), absl::StrCat(name, ": ", part.status().message()));
    }
    const DecodedDracoCloud& first = **decoded[0];
    if (part->geometry != first.geometry) {
      return absl::InvalidArgumentError(
          absl::StrCat(name, " holds a ", GeometryName(part->geometry), " where part 1 holds a ",
                       GeometryName(first.geometry)));
    }
    if (part->attributes != first.attributes) {
      return absl::InvalidArgumentError(absl::StrCat(name, " has the attributes ",
                                                     part->attributes, " where part 1 has ",
                                                     first.attributes));
    }
  }
  parts.reserve(count);
  for (auto& part : decoded) parts.push_back(**std::move(part));
  return parts;
}

absl::StatusOr<DecodedDracoCloud> DecodeDracoPointCloudParts(absl::string_view bytes,
                                                             absl::Span<const uint64_t> part_bytes,
                                                             DracoMeshPolicy policy, int threads) {
  if (part_bytes.empty()) return DecodeDracoPointCloud(bytes, policy);
  absl::StatusOr<std::vector<DecodedDracoCloud>> parts =
      DecodeDracoParts(bytes, part_bytes, policy, threads);
  if (!parts.ok()) return parts.status();
  size_t points = 0;
  for (const DecodedDracoCloud& part : *parts) points += part.cloud.points.size();
  DecodedDracoCloud result;
  result.geometry = parts->front().geometry;
  result.attributes = parts->front().attributes;
  result.cloud.points.reserve(points);
  for (DecodedDracoCloud& part : *parts) {
    const std::vector<Point3f>& p = part.cloud.points;
    result.cloud.points.insert(result.cloud.points.end(), p.begin(), p.end());
    part.cloud.points = std::vector<Point3f>();
  }
  return result;
}

}  // namespace membrane
