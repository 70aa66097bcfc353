// Sample files of `chi2 check`: CSV text or raw little-endian float32 rows.
#pragma once

#include <string>
#include <vector>

#include "ptlab/chi2.h"

namespace ptlab {

/// Reads the points of a sample file with `dims` (2 or 3) coordinates per point.
/// raw = false: text, one point per line, numbers separated by commas and/or spaces; empty lines
/// and lines starting with '#' are skipped, and a first line that does not start with a number
/// is a header. raw = true: little-endian float32, dims per point, nothing else (the file size
/// must be a multiple of 4·dims bytes). Errors name the file, the line and what was expected.
chi2::Status ReadSampleFile(const std::string& path, bool raw, int dims,
                            std::vector<chi2::Point>* points);

/// Where sample `index` (0-based, as ReadSampleFile numbers them) is in the file: "path:LINE"
/// for text, "path: row R (byte B)" for raw files; "path" when the file no longer has it.
/// For messages about a sample found bad after reading (outside the domain).
std::string SampleLocation(const std::string& path, bool raw, int dims, int64_t index);

}  // namespace ptlab
