#include "core/io/binary_scalar.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <limits>

namespace membrane {
namespace {

template <typename T>
T Load(const char* bytes, ByteOrder order) {
  std::array<char, sizeof(T)> buffer;
  std::memcpy(buffer.data(), bytes, sizeof(T));
  const ByteOrder native =
      std::endian::native == std::endian::little ? ByteOrder::kLittleEndian : ByteOrder::kBigEndian;
  if (order != native) std::reverse(buffer.begin(), buffer.end());
  T value;
  std::memcpy(&value, buffer.data(), sizeof(T));
  return value;
}

template <typename T>
void AppendLe(T value, std::string* out) {
  std::array<char, sizeof(T)> buffer;
  std::memcpy(buffer.data(), &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) {
    std::reverse(buffer.begin(), buffer.end());
  }
  out->append(buffer.data(), buffer.size());
}

}  // namespace

size_t ScalarSize(ScalarType type) {
  switch (type) {
    case ScalarType::kInt8:
    case ScalarType::kUint8: return 1;
    case ScalarType::kInt16:
    case ScalarType::kUint16: return 2;
    case ScalarType::kInt32:
    case ScalarType::kUint32:
    case ScalarType::kFloat32: return 4;
    case ScalarType::kFloat64: return 8;
  }
  return 0;
}

bool IsFloatingPoint(ScalarType type) {
  return type == ScalarType::kFloat32 || type == ScalarType::kFloat64;
}

std::optional<ScalarType> ScalarTypeFromPlyName(absl::string_view name) {
  struct Entry {
    absl::string_view name;
    ScalarType type;
  };
  static constexpr Entry kNames[] = {
      {"char", ScalarType::kInt8},      {"int8", ScalarType::kInt8},
      {"uchar", ScalarType::kUint8},    {"uint8", ScalarType::kUint8},
      {"short", ScalarType::kInt16},    {"int16", ScalarType::kInt16},
      {"ushort", ScalarType::kUint16},  {"uint16", ScalarType::kUint16},
      {"int", ScalarType::kInt32},      {"int32", ScalarType::kInt32},
      {"uint", ScalarType::kUint32},    {"uint32", ScalarType::kUint32},
      {"float", ScalarType::kFloat32},  {"float32", ScalarType::kFloat32},
      {"double", ScalarType::kFloat64}, {"float64", ScalarType::kFloat64},
  };
  for (const Entry& entry : kNames) {
    if (entry.name == name) return entry.type;
  }
  return std::nullopt;
}

double DecodeScalar(const char* bytes, ScalarType type, ByteOrder order) {
  switch (type) {
    case ScalarType::kInt8: return Load<int8_t>(bytes, order);
    case ScalarType::kUint8: return Load<uint8_t>(bytes, order);
    case ScalarType::kInt16: return Load<int16_t>(bytes, order);
    case ScalarType::kUint16: return Load<uint16_t>(bytes, order);
    case ScalarType::kInt32: return Load<int32_t>(bytes, order);
    case ScalarType::kUint32: return Load<uint32_t>(bytes, order);
    case ScalarType::kFloat32: return Load<float>(bytes, order);
    case ScalarType::kFloat64: return Load<double>(bytes, order);
  }
  return 0;
}

float NarrowToFloat(double value) {
  // Values just above float's maximum still round to it; from the midpoint between it and
  // 2^128 on (half its last-place unit, 2^103, above it) rounding goes to infinity.
  constexpr double kOverflow = static_cast<double>(std::numeric_limits<float>::max()) + 0x1p103;
  if (value >= kOverflow) return std::numeric_limits<float>::infinity();
  if (value <= -kOverflow) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

void AppendFloat32Le(float value, std::string* out) { AppendLe(value, out); }
void AppendFloat64Le(double value, std::string* out) { AppendLe(value, out); }
void AppendInt32Le(int32_t value, std::string* out) { AppendLe(value, out); }
void AppendUint32Le(uint32_t value, std::string* out) { AppendLe(value, out); }

}  // namespace membrane
