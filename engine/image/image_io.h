// Reading (EXR, PNG, Radiance HDR, PFM) and atomic writing (EXR, PNG, PFM) of linear RGB images.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/core/status.h"
#include "engine/image/atomic_file.h"  // WriteFileAtomically, PrepareOutputFile
#include "engine/image/image.h"

namespace ptlab {

/// File formats ReadImage understands; recognised by their magic bytes, not by the extension.
enum class ImageFormat { kUnknown, kExr, kPng, kHdr, kPfm };

/// "EXR", "PNG", "HDR", "PFM" or "unknown".
const char* ImageFormatName(ImageFormat format);

/// The format whose magic bytes start `bytes` (`size` bytes available), or kUnknown.
/// EXR: 76 2f 31 01; PNG: 89 'PNG' 0d 0a 1a 0a; HDR: "#?RADIANCE" or "#?RGBE";
/// PFM: "PF"/"Pf" + whitespace.
ImageFormat DetectImageFormat(const unsigned char* bytes, size_t size);

/// Reads an image as linear RGB (row 0 at the top), detecting the format by its magic bytes:
/// - EXR (OpenEXR, any compression, half or float): channels R,G,B (A and others ignored), or a
///   single Y channel replicated to RGB; the data window gives the size.
/// - PNG (8 or 16 bit, grey/RGB with or without alpha; alpha ignored): decoded from sRGB to
///   linear with the exact piecewise curve.
/// - Radiance HDR (RGBE): linear, as stored.
/// - PFM ("PF" RGB or "Pf" grey): the sign of the scale gives the byte order (negative = little
///   endian), rows are stored bottom to top; the magnitude of the scale is ignored.
/// Errors name the file and what was wrong (missing, empty, truncated, unknown format, bad header).
StatusOr<Image> ReadImage(const std::string& path);

/// The extension of `path` in lower case, with its dot (".png"), or "": what WriteImage goes by.
std::string LowercaseExtension(const std::string& path);

/// ReadImage of bytes already in memory; `path` only names them in errors (the fuzz
/// harnesses of tests/fuzz/ call this).
StatusOr<Image> DecodeImage(const std::string& path, const std::string& bytes);

/// The string attributes of an EXR file's header, as (name, value), sorted by name.
StatusOr<std::vector<std::pair<std::string, std::string>>> ReadExrStringAttributes(
    const std::string& path);

/// Writes `image` as an OpenEXR file: scanline, ZIP, 32-bit float R,G,B, plus each
/// (name, value) of `header_attributes` as a string attribute. Atomic (see WriteFileAtomically).
/// Names must be non-empty and must not be standard attributes ("channels", "compression", ...).
Status WriteExr(const std::string& path, const Image& image,
                const std::vector<std::pair<std::string, std::string>>& header_attributes = {});
/// The bytes WriteExr writes; `path` only names the file in errors.
StatusOr<std::string> EncodeExr(
    const std::string& path, const Image& image,
    const std::vector<std::pair<std::string, std::string>>& header_attributes = {});

/// Writes `image` as an 8-bit RGB PNG: each channel sRGB-encoded with the exact curve, clamped to
/// [0, 1] and rounded to nearest; NaN becomes 0. Atomic.
Status WritePng(const std::string& path, const Image& image);
/// The bytes WritePng writes; `path` only names the file in errors.
StatusOr<std::string> EncodePng(const std::string& path, const Image& image);

/// Writes `image` as a little-endian RGB PFM (scale -1, rows bottom to top), floats bit-exact.
/// Atomic.
Status WritePfm(const std::string& path, const Image& image);

/// Writes by the extension of `path` (case-insensitive): .exr, .png or .pfm; other extensions are
/// an error. EXR gets no extra header attributes.
Status WriteImage(const std::string& path, const Image& image);

}  // namespace ptlab
