#include "core/render/png_codec.h"

#include <png.h>

#include "absl/strings/str_cat.h"

namespace membrane {

absl::StatusOr<std::string> EncodePng(const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != size_t(image.width) * image.height * 3) {
    return absl::InvalidArgumentError(absl::StrCat("cannot write a PNG of ", image.width, " x ",
                                                   image.height, " pixels from ",
                                                   image.pixels.size(), " bytes"));
  }
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  // First the size, then the bytes.
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, image.pixels.data(), 0, nullptr)) {
    std::string reason = png.message;
    png_image_free(&png);
    return absl::InternalError(absl::StrCat("libpng cannot encode the picture: ", reason));
  }
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.pixels.data(), 0, nullptr)) {
    std::string reason = png.message;
    png_image_free(&png);
    return absl::InternalError(absl::StrCat("libpng cannot encode the picture: ", reason));
  }
  bytes.resize(size);
  return bytes;
}

absl::StatusOr<RgbImage> DecodePng(absl::string_view bytes) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&png, bytes.data(), bytes.size())) {
    return absl::InvalidArgumentError(absl::StrCat("not a PNG file: ", png.message));
  }
  if (uint64_t(png.width) * png.height > (uint64_t(1) << 26)) {
    png_image_free(&png);
    return absl::InvalidArgumentError(
        absl::StrCat("a PNG of ", png.width, " x ", png.height, " pixels is too large"));
  }
  png.format = PNG_FORMAT_RGB;
  RgbImage image(static_cast<int>(png.width), static_cast<int>(png.height), 0);
  if (!png_image_finish_read(&png, nullptr, image.pixels.data(), 0, nullptr)) {
    std::string reason = png.message;
    png_image_free(&png);
    return absl::InvalidArgumentError(absl::StrCat("corrupt PNG file: ", reason));
  }
  return image;
}

}  // namespace membrane
