// CRC-32C (Castagnoli), the checksum of uploads and results on the wire: cheap, and enough to
// catch truncation and corruption in transit (it is not a defence against forgery).
#ifndef MEMBRANE_PROTO_CRC32C_H_
#define MEMBRANE_PROTO_CRC32C_H_

#include <cstdint>

#include "absl/strings/string_view.h"

namespace membrane {

// The CRC-32C of `bytes` continued from `crc` (0 to start): Crc32c(b, Crc32c(a)) equals
// Crc32c(a + b), so chunks can be checksummed as they arrive. Crc32c("123456789") is
// 0xE3069283.
uint32_t Crc32c(absl::string_view bytes, uint32_t crc = 0);

}  // namespace membrane

#endif  // MEMBRANE_PROTO_CRC32C_H_
