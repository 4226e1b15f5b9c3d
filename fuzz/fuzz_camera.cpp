// libFuzzer target: the camera JSON loader (loadCameraJson) on arbitrary bytes.
// Properties: it returns a camera that passes validateCamera, or throws ssrcl::Error naming the
// file; a camera it returns survives saveCameraJson + loadCameraJson exactly. Anything else
// (another exception, a crash, a sanitizer report) is a bug.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "fuzz_input_file.hpp"
#include "ssrcl/camera.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = ssrcl::fuzz::inputPath("camera.json");
  static const std::string again = ssrcl::fuzz::inputPath("camera-saved.json");
  ssrcl::fuzz::writeInput(path, data, size);
  ssrcl::Camera camera;
  try {
    camera = ssrcl::loadCameraJson(path);
  } catch (const ssrcl::Error& e) {
    if (std::string(e.what()).rfind(path + ": ", 0) != 0) std::abort();
    return 0;
  }
  try {
    ssrcl::validateCamera(camera, "fuzzed camera");
    ssrcl::saveCameraJson(again, camera);
    const ssrcl::Camera back = ssrcl::loadCameraJson(again);
    if (back.view != camera.view || back.projection != camera.projection || back.width != camera.width ||
        back.height != camera.height || back.nearPlane != camera.nearPlane || back.farPlane != camera.farPlane)
      std::abort();
  } catch (const ssrcl::Error&) {
    std::abort();  // a camera the loader accepted must validate and round-trip
  }
  return 0;
}
