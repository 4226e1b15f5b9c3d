#include "device_frame_stages.hpp"

#include "io/conventions.hpp"
#include "pipeline/back_pyramid_stage.hpp"
#include "pipeline/color_pyramid_stage.hpp"
#include "pipeline/device_impl.hpp"
#include "pipeline/hzb_stage.hpp"
#include "pipeline/setup_stage.hpp"
#include "pipeline/thickness_stage.hpp"

namespace ssrcl::bench {

using namespace ssrcl::detail;

namespace {
const StageAccess kReadBack{"the roofline", {Role::DepthPyramid, Role::Planes, Role::BackPyramid, Role::ColorPyramid}, {}};

double stageMs(const StageEvents& events, const std::string& stage) {
  double ms = 0;
  const auto it = events.find(stage);
  if (it != events.end())
    for (const cl::Event& e : it->second) ms += eventMs(e);
  return ms;
}
}  // namespace

struct DeviceFrameStages::Impl {
  const Device handle;  // shares the device with the caller's handle, which may go first
  Device::Impl& device;
  const GBuffer& g;
  const Camera camera;
  const TraceSettings settings;
  const FrameShape frame;
  SetupStage setup;
  HzbStage hzb;
  ThicknessStage thickness;
  BackPyramidStage back;
  ColorPyramidStage colors;
  DeviceBuffers buffers;
  FrameResources resources;

  Impl(const Device& d, const GBuffer& gbuffer, const Camera& cam, const TraceSettings& s)
      : handle(d), device(DeviceAccess::impl(handle)), g(gbuffer), camera(cam), settings(s), frame(cam.width, cam.height) {
    if (!s.prefilter) throw std::invalid_argument("device frame stages: the colour pyramid needs settings.prefilter");
    setup.configure(device);
    hzb.configure(device);
    thickness.configure(device, s, false);
    back.configure(device, true, false);
    colors.configure(device, s, false);
    resources.beginPlan();
    setup.plan(resources, buffers, frame, g.color.channels, !s.constantRoughness, false);
    thickness.plan(resources, buffers, frame);
    hzb.plan(resources, buffers, frame);
    back.plan(resources, buffers, frame);
    colors.plan(resources, buffers, frame);
    buffers.allocate(device, "the roofline's frame");
    setup.bind(resources);
    thickness.bind(resources);
    hzb.bind(device.queue, resources);
    back.bind(resources);
    colors.bind(resources);
  }

  template <class T>
  std::vector<T> read(Role role, size_t count) const {
    std::vector<T> out(count);
    device.queue.enqueueReadBuffer(resources.read(kReadBack, role), CL_TRUE, 0, count * sizeof(T), out.data());
    return out;
  }
};

DeviceFrameStages::DeviceFrameStages(const Device& device, const GBuffer& gbuffer, const Camera& camera,
                                     const TraceSettings& settings)
    : impl_(std::make_unique<Impl>(device, gbuffer, camera, settings)) {}
DeviceFrameStages::~DeviceFrameStages() = default;

FrameStageMs DeviceFrameStages::run() {
  Impl& m = *impl_;
  cl::CommandQueue& q = m.device.queue;
  const FrameConstants constants = frameConstants(m.frame, m.camera, m.settings);
  // A map of events a stage: the range pyramid's go under "hzb" as the HZB's do.
  StageEvents setup, hzb, thickness, back, colors;
  m.setup.enqueue(q,
                  {m.g.color.data.data(), m.g.depth.data.data(), m.g.normal.data.data(),
                   m.settings.constantRoughness ? nullptr : m.g.roughness.data.data()},
                  SetupStage::params(constants, m.settings, m.g.color.channels), setup);
  m.hzb.enqueue(q, hzb);
  m.thickness.enqueue(q, constants, m.settings, nullptr, !isPerspective(m.camera), thickness);
  m.back.enqueue(q, constants, back);
  m.colors.reduce(q, colors);
  q.finish();
  return {stageMs(setup, "setup"), stageMs(hzb, "hzb"), stageMs(thickness, "thickness"), stageMs(back, "hzb"),
          stageMs(colors, "color_mips")};
}

std::vector<float> DeviceFrameStages::hzb() const {
  return impl_->read<float>(Role::DepthPyramid, impl_->frame.pyramidTexels());
}
std::vector<glm::vec4> DeviceFrameStages::planes() const {
  return impl_->read<glm::vec4>(Role::Planes, impl_->frame.pixels());
}
std::vector<glm::vec2> DeviceFrameStages::rangePyramid() const {
  return impl_->read<glm::vec2>(Role::BackPyramid, impl_->frame.pyramidTexels());
}
std::vector<glm::vec4> DeviceFrameStages::colorPyramid() const {
  return impl_->read<glm::vec4>(Role::ColorPyramid, impl_->frame.pyramidTexels());
}

}  // namespace ssrcl::bench
