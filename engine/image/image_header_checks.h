// Checks of an image file's header against its size, before a decoder allocates what the header
// claims (engine/image/image_io.cpp calls them; the fuzz harnesses reach them through DecodeImage).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace ptlab {

// The most pixels one byte of a file can decode to, per format, with margin: Radiance RLE
// packs a run of 127 pixels in 2 bytes per channel (4 channels); EXR's ZIP (deflate, at most
// about 1032:1) over a half-float channel; PNG's deflate over 1-bit pixels. A header that
// claims more pixels than the file can hold is refused before the pixels are allocated.
constexpr int64_t kMaxHdrPixelsPerByte = 32;
constexpr int64_t kMaxExrPixelsPerByte = 1100;
constexpr int64_t kMaxPngPixelsPerByte = 8300;

/// Empty when a w x h image fits in `file_bytes` of a format decoding at most
/// `pixels_per_byte`; else the reason.
std::string ClaimedSizeError(int64_t w, int64_t h, size_t file_bytes, int64_t pixels_per_byte);

/// Empty when every byte stb_image will read of a Radiance HDR body (a w x h image from byte 0
/// of `bytes` on, the header already consumed by the caller's offset rules) is there; else the
/// reason. See the .cpp for stb's rules.
std::string HdrBodyError(const std::string& bytes, int64_t w, int64_t h);

/// Empty when no attribute size in the OpenEXR header(s) of `bytes` exceeds what the rest of
/// the file can hold; else the reason.
std::string ExrHeaderError(const std::string& bytes);

}  // namespace ptlab
