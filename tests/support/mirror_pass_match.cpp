#include "support/mirror_pass_match.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "support/exr_fixtures.hpp"

namespace ssrcl::test {

MirrorPassMatch matchExactReflections(const std::string& output, const Scene& scene, const Camera& camera) {
  ExrContents exr = readExr(output);
  if (exr.width != camera.width || exr.height != camera.height)
    throw std::runtime_error(output + ": not the camera's size");
  const MirrorTruth truth = exactMirrorReflection(scene, camera, renderGBuffer(scene, camera));
  const std::vector<float>* rgb[3] = {&exr.channels.at("R").values, &exr.channels.at("G").values,
                                      &exr.channels.at("B").values};
  const std::vector<float>& a = exr.channels.at("A").values;
  MirrorPassMatch m;
  for (int y = 0; y < exr.height; ++y)
    for (int x = 0; x < exr.width; ++x) {
      const MirrorSample& s = truth.at(x, y);
      const std::size_t i = std::size_t(y) * exr.width + x;
      if (s.cls == ReflectionClass::Visible) {
        ++m.visible;
        double err = 0;
        for (int c = 0; c < 3; ++c) err = std::max(err, std::abs((*rgb[c])[i] - s.color[c]));
        m.visibleOk += err <= 0.05 + s.colorSpread + 1e-3 && a[i] == 1.0f;
      } else if (s.cls == ReflectionClass::Sky || s.cls == ReflectionClass::OffScreen) {
        ++m.missed;
        m.missedOk += a[i] == 0.0f;
      }
    }
  return m;
}

}  // namespace ssrcl::test
