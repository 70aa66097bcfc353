// Reading a bitmap texture's image (stb_image for the 8/16-bit formats, ReadImage for the rest).
#include "engine/image/texture_image.h"

#include <cmath>
#include <limits>
#include <cstdint>

#include "engine/core/input_file.h"
#include "engine/core/memory_budget.h"
#include "engine/image/image_header_checks.h"
#include "engine/image/image_io.h"
#include "engine/image/srgb.h"
#include <stb/stb_image.h>

namespace ptlab {

StatusOr<Image> ReadTextureImage(const std::string& path, bool raw) {
  // A regular file of at most 2 GiB: a FIFO or /dev/zero read forever, a directory threw
  // std::ios_base::failure past main.
  std::string bytes;
  PTLAB_RETURN_IF_ERROR(ReadInputFile(path, "the texture image", &bytes));
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const ImageFormat format = DetectImageFormat(data, bytes.size());
  Image image;
  if (format == ImageFormat::kExr || format == ImageFormat::kHdr || format == ImageFormat::kPfm) {
    StatusOr<Image> read = DecodeImage(path, bytes);
    if (!read.ok()) return read.status();
    image = std::move(*read);
  } else {
    if (bytes.size() > size_t(std::numeric_limits<int>::max()))
      return Status::Error(path + ": texture image too large");
    const int len = int(bytes.size());
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(data, len, &w, &h, &comp) || w <= 0 || h <= 0 ||
        int64_t(w) * int64_t(h) > (int64_t(1) << 28))
      return Status::Error(path + ": not a texture image ptlab reads (EXR, HDR, PFM, PNG, JPEG, " +
                           "BMP, TGA) or bad header: " + stbi_failure_reason() +
                           " (at most 2^28 pixels)");
    // A header may not claim more pixels than its bytes can decode to (a 71-byte PNG claiming
    // 16000 x 16000 pixels peaked at 3.0 GB before stb failed on its missing data).
    if (const std::string claimed = ClaimedSizeError(w, h, bytes.size(), kMaxPngPixelsPerByte);
        !claimed.empty())
      return Status::Error(path + ": " + claimed);
    // Decoding takes 3 bytes a pixel (stb), 12 (floats) and 12 more in the scene's texture
    // table: within what a file of this size may expand into (--max-memory).
    if (const std::string over = OverExpansionBudget(
            30.0 * double(w) * double(h), bytes.size(),
            "the texture's " + std::to_string(w) + "x" + std::to_string(h) + " pixels");
        !over.empty())
      return Status::Error(path + ": " + over);
    image = Image(w, h);
    const size_t n = image.rgb.size();
    if (stbi_is_16_bit_from_memory(data, len)) {
      stbi_us* pixels = stbi_load_16_from_memory(data, len, &w, &h, &comp, 3);
      if (!pixels) return Status::Error(path + ": bad texture image: " + stbi_failure_reason());
      for (size_t i = 0; i < n; ++i) {
        const float v = float(pixels[i] / 65535.0);
        image.rgb[i] = raw ? v : SrgbToLinear(v);
      }
      stbi_image_free(pixels);
    } else {
      stbi_uc* pixels = stbi_load_from_memory(data, len, &w, &h, &comp, 3);
      if (!pixels) return Status::Error(path + ": bad texture image: " + stbi_failure_reason());
      float table[256];
      for (int v = 0; v < 256; ++v) {
        const float x = float(v / 255.0);
        table[v] = raw ? x : SrgbToLinear(x);
      }
      for (size_t i = 0; i < n; ++i) image.rgb[i] = table[pixels[i]];
      stbi_image_free(pixels);
    }
  }
  for (float& v : image.rgb)
    if (!std::isfinite(v)) v = 0.0f;
  return image;
}

}  // namespace ptlab
