// Reading a bitmap texture's image: EXR / HDR / PFM (linear) and the 8- or 16-bit formats stb_image
// decodes (PNG, JPEG, BMP, TGA), sRGB-decoded to linear unless `raw`.
#pragma once

#include <string>

#include "engine/core/status.h"
#include "engine/image/image.h"

namespace ptlab {

/// The texels of a bitmap texture as linear RGB, row 0 at the top (Mitsuba 3's `bitmap`):
/// - EXR, Radiance HDR, PFM: ReadImage (linear as stored; `raw` changes nothing);
/// - PNG, JPEG, BMP, TGA (stb_image; grey replicated to RGB, alpha ignored): value / 255 (or
///   / 65535 for 16-bit PNG), then decoded from sRGB with the exact curve unless `raw`.
/// Texels that are not finite become 0. Errors name the file.
StatusOr<Image> ReadTextureImage(const std::string& path, bool raw);

}  // namespace ptlab
