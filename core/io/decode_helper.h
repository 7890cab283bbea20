// The child side of DecodeInSubprocess (decode_subprocess.h): decodes one Draco point cloud
// from stdin and writes its points to stdout. membrane-decode is nothing else; the membrane
// client runs it as `membrane --decode-helper ...` on itself, so it needs no second binary.
#ifndef MEMBRANE_CORE_IO_DECODE_HELPER_H_
#define MEMBRANE_CORE_IO_DECODE_HELPER_H_

#include <string>
#include <vector>

namespace membrane {

// Exit statuses of RunDecodeHelper besides 0 (the points were written).
inline constexpr int kDecodeHelperRejected = 3;   // not an acceptable cloud; one line on stderr
inline constexpr int kDecodeHelperOverLimit = 4;  // more points than MAX_POINTS
// The argument after MAX_POINTS that makes a Draco mesh give its vertices.
inline constexpr char kAcceptMeshArgument[] = "--accept-mesh";
// The argument after MAX_POINTS that decodes a mesh, faces and all.
inline constexpr char kMeshArgument[] = "--mesh";
// The argument prefix that gives a point cloud's parts: kPartsArgument then their sizes in
// bytes, comma-separated (draco_parts.h).
inline constexpr char kPartsArgument[] = "--parts=";
// The argument prefix that gives the threads the parts are decoded on (default 1).
inline constexpr char kThreadsArgument[] = "--threads=";

// `args`: MAX_POINTS, then optionally kAcceptMeshArgument or kMeshArgument, and for a point
// cloud optionally kPartsArgument and kThreadsArgument. Reads all of stdin
// and decodes it: with DecodeDracoPointCloudParts it writes the point count as a little-endian
// uint64, then x y z float32 per point, to stdout; with kMeshArgument, DecodeDracoMesh, and it
// writes the vertices so, then the face count and three int32 indices per face. MAX_POINTS
// bounds the points or the vertices. Returns the process exit status: 0, or
// kDecodeHelperRejected (also for bad arguments) or kDecodeHelperOverLimit with one line on
// stderr naming the problem.
int RunDecodeHelper(const std::vector<std::string>& args);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_DECODE_HELPER_H_
