// Uses the installed library through its public API only: a mirror wall facing the camera
// reflects what is behind the camera, which is not on screen, so the pass is written into the
// caller's memory as zeros; the version matches the headers, and misuse is an error.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "ssrcl/ssrcl.hpp"

int main() {
  if (std::strcmp(ssrcl::versionString(), SSRCL_VERSION) != 0 || ssrcl::versionNumber() != SSRCL_VERSION_NUMBER) {
    std::printf("library %s, headers %s\n", ssrcl::versionString(), SSRCL_VERSION);
    return 1;
  }
  const int w = 32, h = 24;
  ssrcl::Camera camera;
  camera.width = w;
  camera.height = h;
  camera.projection = glm::perspective(1.0, double(w) / h, 0.1, 100.0);
  camera.nearPlane = 0.1;
  camera.farPlane = 100.0;
  std::vector<float> color(size_t(w) * h * 3, 0.5f), depth(size_t(w) * h, 5.0f), normal(size_t(w) * h * 3, 0.0f);
  for (size_t i = 0; i < depth.size(); ++i) normal[i * 3 + 2] = 1.0f;  // facing the camera
  std::vector<float> reflection(size_t(w) * h * 4, -1.0f);

  try {
    ssrcl::Device device(ssrcl::DeviceType::CPU);
    ssrcl::Pipeline pipeline(device);
    try {
      pipeline.execute();
      std::printf("execute() before commit() did not throw\n");
      return 1;
    } catch (const ssrcl::Error& e) {
      if (e.code() != ssrcl::ErrorCode::InvalidOperation) throw;
    }
    pipeline.setImage("color", ssrcl::ImageView(color.data(), w, h, 3));
    pipeline.setImage("depth", ssrcl::ImageView(depth.data(), w, h, 1));
    pipeline.setImage("normal", ssrcl::ImageView(normal.data(), w, h, 3));
    pipeline.setOutput("reflection", ssrcl::ImageView(reflection.data(), ssrcl::PixelFormat::Float, w, h, 4));
    pipeline.setCamera(camera);
    pipeline.settings().constantRoughness = 0.0f;
    int reports = 0;
    pipeline.setProgressMonitor([&](double) { return ++reports > 0; });
    pipeline.commit();
    pipeline.execute();
    for (float v : reflection)
      if (!std::isfinite(v) || v < 0.0f) {
        std::printf("output not written or not finite: %g\n", v);
        return 1;
      }
    if (reports == 0) {
      std::printf("the progress monitor was not called\n");
      return 1;
    }
  } catch (const ssrcl::Error& e) {
    std::printf("ssrcl error (%s): %s\n", ssrcl::errorCodeName(e.code()), e.what());
    return 1;
  }
  std::printf("ssrcl %s: ok\n", ssrcl::versionString());
  return 0;
}
