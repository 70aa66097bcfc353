// libFuzzer harness: CS184 camera settings files (`ptlab render -c`).
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/io/cs184_camera_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  ptlab::CameraDesc camera;
  camera.width = 64, camera.height = 48;
  (void)ptlab::ApplyCs184CameraSettings(text, "fuzz.cam", &camera);
  return 0;
}
