// The image harnesses' body: decode bytes that start with `magic` (prepended when missing, so
// the fuzzer spends its time inside one format's reader).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "engine/image/image_io.h"

inline int FuzzImageDecoder(const uint8_t* data, size_t size, const std::string& magic) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (bytes.compare(0, magic.size(), magic) != 0) bytes.insert(0, magic);
  (void)ptlab::DecodeImage("fuzz", bytes);
  return 0;
}
