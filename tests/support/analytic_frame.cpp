#include "support/analytic_frame.hpp"

#include "scenes/analytic_scene.hpp"

namespace ssrcl::test {

AnalyticFrame renderAnalyticFrame(const std::string& name, int width, int height, double eyeShiftX) {
  const Scene scene = makeScene(name);
  ViewParams view = scene.view;
  view.eye.x += eyeShiftX;
  AnalyticFrame f;
  f.camera = makeCamera(view, width, height);
  AnalyticGBuffer g = renderGBuffer(scene, f.camera);
  f.g = static_cast<GBuffer&>(g);
  return f;
}

void runFrame(Pipeline& pipeline, const AnalyticFrame& frame, const TraceSettings& settings) {
  pipeline.setGBuffer(frame.g);
  pipeline.setCamera(frame.camera);
  pipeline.settings() = settings;
  pipeline.commit();
  pipeline.execute();
}

}  // namespace ssrcl::test
