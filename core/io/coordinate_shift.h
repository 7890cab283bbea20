// Moving clouds near the origin as they are read. Georeferenced scans carry coordinates such as
// UTM eastings and northings (500,000 and 4,000,000 m) or ECEF positions, where float32 values
// lie 0.03 to 0.5 m apart: coarser than a scan's detail, and the core computes in float32. The
// readers of text and of binary doubles subtract a whole-unit offset in double before
// narrowing, so nothing of the file's precision is lost, and record it as the geometry's origin
// for the writers. Binary float32 positions (PLY, PCD, STL, Draco) are taken as they are:
// moving them would gain no precision, and would hide their coarse lattice from Voxelize's
// precision check, which refuses such clouds instead of giving a wrong genus.
#ifndef MEMBRANE_CORE_IO_COORDINATE_SHIFT_H_
#define MEMBRANE_CORE_IO_COORDINATE_SHIFT_H_

#include "absl/status/status.h"
#include "core/geometry/point_cloud.h"
#include "core/io/file_format.h"

namespace membrane {

// Coordinates from this magnitude on are moved: float32 values there lie 0.001 apart or more.
// Below it nothing changes, so the clouds of CAD models and lab scans keep their coordinates.
inline constexpr double kShiftFrom = 1e4;
// Nor are coordinates moved beyond this magnitude (2^40, about 10^12): no survey coordinate is
// that large, and a first point out there is an outlier that must not set the frame.
inline constexpr double kShiftUpTo = 1099511627776.0;

// One reader's conversion of file coordinates to float32 positions. Not thread-safe: one per
// read.
class CoordinateShift {
 public:
  // (x, y, z) minus the origin, each narrowed with NarrowToFloat (infinite beyond float's
  // range, NaN kept, so that the finiteness checks report them). The first call whose three
  // coordinates are finite fixes the origin: on each axis where that coordinate's magnitude is
  // in [kShiftFrom, kShiftUpTo], the coordinate rounded to a whole unit; 0 on the others.
  Point3f Narrow(double x, double y, double z);

  // The position of values a binary file stores as `binary_float32` (all three) or not: float32
  // values as they are, anything else through Narrow. Moving float32 values gains no precision,
  // and would hide their lattice from Voxelize's precision check (see the top of this file).
  Point3f NarrowStored(double x, double y, double z, bool binary_float32);

  // The origin fixed so far: zero before the first finite point and when nothing is moved.
  const Origin3d& origin() const { return origin_; }

 private:
  void Fix(double x, double y, double z);

  bool fixed_ = false;
  Origin3d origin_{0, 0, 0};
};

// OK unless `origin` is not zero and `format` stores float32 positions only (STL, Draco): the
// positions would have to leave the origin, and the file's precision with it. InvalidArgument
// then, naming the origin and the formats that keep it (for `use`).
absl::Status CheckOriginFitsFormat(const Origin3d& origin, FileFormat format, FileUse use);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_COORDINATE_SHIFT_H_
