#pragma once
// Auxiliary views (kernels/view_trace.cl): other G-buffers of the same scene, each with its own
// camera. Every view runs the main frame's own setup, thickness, HZB, range and colour pyramid
// stages on its images; after each trace batch, the rays the main frame left unresolved continue
// in them.
#include <memory>

#include "back_pyramid_stage.hpp"
#include "color_pyramid_stage.hpp"
#include "pipeline_inputs.hpp"
#include "setup_stage.hpp"
#include "thickness_stage.hpp"
#include "trace_stage.hpp"

namespace ssrcl::detail {

using shared::ViewCamera;
using shared::ViewTraceParams;

struct ViewSource {
  PipelineInputs inputs;  // color, depth, normal, roughness (as the main frame's)
  Camera camera;
  std::string label;       // names the view in messages ("view 1" when empty)
  bool otherTime = false;  // rendered at another moment: hits the frame sees moved are not taken
  bool prepared = false;   // its device images hold its setup, HZB, colours and thickness
};

class ViewStage {
 public:
  // Throws Error naming the view when its camera or images cannot be used.
  static void validate(const ViewSource& view, int index, const TraceSettings& s);
  static std::string name(const ViewSource& view, int index);
  // The trace in the views reads the main frame's pixels and rays and continues its rays ...
  static const StageAccess access;
  // ... in each view's own frame.
  static const StageAccess viewAccess;

  void configure(Device::Impl& device, const TraceSettings& s, size_t viewCount);
  // `rayRecords`: the trace's ray records (pixels x batch size).
  void plan(DeviceBuffers& buffers, const std::vector<ViewSource>& views, size_t rayRecords);
  void bind(cl::CommandQueue& q, const Camera& main, const std::vector<ViewSource>& views,
            const FrameResources& resources);
  // The setup, HZB, colour pyramid and thickness of each view not yet prepared.
  void prepare(cl::CommandQueue& q, std::vector<ViewSource>& views, const TraceSettings& s, StageEvents& events);
  // The unresolved rays of one trace batch, in their views ("views" events).
  void trace(cl::CommandQueue& q, const TraceParams& batch, StageEvents& events);
  // Caps the mean rgb of view hits at `cap` times the frame's 99th percentile (0: no cap): as
  // bright as the frame's lit surfaces may be, a light source may not. A lamp the frame does not
  // show but a view does (a ceiling lamp above the camera) is met by the few rays of a lobe's tail:
  // bright and rare, it adds speckle that costs more than the light it brings
  // (TraceSettings::viewRadianceCap).
  void limitRadiance(const float* color, size_t pixels, int channels, float cap);
  size_t count() const { return units_.size(); }

 private:
  struct Unit {
    FrameShape frame;
    FrameResources resources;  // the view's own frame
    SetupStage setup;
    ThicknessStage thickness;
    HzbStage hzb;
    BackPyramidStage range;  // what the trace skips (kernels/back_pyramid.cl)
    ColorPyramidStage colors;
    cl::Kernel kernel;  // trace_views bound to this view's buffers
  };
  std::vector<std::unique_ptr<Unit>> units_;  // stable addresses: DeviceBuffers keeps pointers
  cl::Program program_;
  cl::Buffer cameras_;    // ViewCamera per view
  cl::Buffer viewOrder_;  // per ray record: its best views, a byte per rank (kernels/view_trace.cl)
  std::vector<int> colorChannels_;
  float radianceLimit_ = 0.0f;
};

}  // namespace ssrcl::detail
