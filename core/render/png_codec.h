// RGB pictures and their PNG files (libpng's simplified API: no setjmp/longjmp here).
#ifndef MEMBRANE_CORE_RENDER_PNG_CODEC_H_
#define MEMBRANE_CORE_RENDER_PNG_CODEC_H_

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace membrane {

// 8-bit RGB, rows top to bottom, 3 bytes a pixel.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> pixels;  // width * height * 3

  RgbImage() = default;
  RgbImage(int w, int h, uint32_t rgb) : width(w), height(h), pixels(size_t(w) * h * 3) {
    for (size_t i = 0; i < pixels.size(); i += 3) {
      pixels[i] = uint8_t(rgb >> 16);
      pixels[i + 1] = uint8_t(rgb >> 8);
      pixels[i + 2] = uint8_t(rgb);
    }
  }
  // The pixel at (x, y) as 0xRRGGBB.
  uint32_t At(int x, int y) const {
    const uint8_t* p = &pixels[(size_t(y) * width + x) * 3];
    return uint32_t(p[0]) << 16 | uint32_t(p[1]) << 8 | p[2];
  }
};

// `image` as a PNG file. InvalidArgument for an empty image or one whose pixels do not match
// its size; Internal when libpng fails.
absl::StatusOr<std::string> EncodePng(const RgbImage& image);

// The RGB picture of the PNG file `bytes` (any colour type, converted). InvalidArgument naming
// libpng's reason when the bytes are not a PNG file or the picture is over 2^26 pixels.
absl::StatusOr<RgbImage> DecodePng(absl::string_view bytes);

}  // namespace membrane

#endif  // MEMBRANE_CORE_RENDER_PNG_CODEC_H_
