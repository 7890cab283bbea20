// Fixed-width numbers in binary files (PLY, PCD, STL): their types, decoding from either
// byte order, and little-endian encoding for the writers.
#ifndef MEMBRANE_CORE_IO_BINARY_SCALAR_H_
#define MEMBRANE_CORE_IO_BINARY_SCALAR_H_

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "absl/strings/string_view.h"

namespace membrane {

enum class ScalarType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

enum class ByteOrder { kLittleEndian, kBigEndian };

// The size of one value of `type` in bytes: 1, 2, 4 or 8.
size_t ScalarSize(ScalarType type);

// True for kFloat32 and kFloat64.
bool IsFloatingPoint(ScalarType type);

// The type a PLY header names: "char", "uchar", "short", "ushort", "int", "uint", "float",
// "double" and their sized aliases "int8" ... "float64"; nullopt for anything else.
std::optional<ScalarType> ScalarTypeFromPlyName(absl::string_view name);

// The value of `type` stored at `bytes` in `order`, widened to double (exact for every type
// here). The caller guarantees ScalarSize(type) readable bytes at `bytes`; no alignment needed.
double DecodeScalar(const char* bytes, ScalarType type, ByteOrder order);

// `value` rounded to float; magnitudes beyond float's range become +-infinity (a plain cast
// would be undefined behaviour) so that the finiteness checks report them.
float NarrowToFloat(double value);

// Appends `value` to *out as 4 little-endian bytes.
void AppendFloat32Le(float value, std::string* out);
void AppendFloat64Le(double value, std::string* out);
void AppendInt32Le(int32_t value, std::string* out);
void AppendUint32Le(uint32_t value, std::string* out);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_BINARY_SCALAR_H_
