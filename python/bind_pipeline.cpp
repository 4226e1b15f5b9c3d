#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "numpy_image.hpp"
#include "ssrcl/frame.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::python {
namespace {

// A Pipeline for Python. Its inputs are owned here (the C++ pipeline reads them at commit and
// execute), and the arrays output() hands out view the C++ pipeline's own buffers, no copy. Such
// a view keeps that C++ pipeline alive; since commit() and execute() rewrite or reallocate those
// buffers, they first move to a fresh C++ pipeline (same device, images, camera, settings) while
// views of the old one are alive, so a view never changes under its reader nor dangles.
class PythonPipeline {
 public:
  explicit PythonPipeline(const Device& device) : device_(device), pipeline_(std::make_shared<Pipeline>(device)) {}

  // `keeper` keeps the pixels `view` points at alive until they are replaced.
  void setImage(const std::string& name, const ImageView& view, std::shared_ptr<const void> keeper) {
    pipeline_->setImage(name, view);  // validates the name first; the commit stands (the C++ rule)
    inputs_[name] = {view, std::move(keeper)};
  }

  // No such input any more (an empty Image unsets it in the C++ pipeline, which keeps nothing of it).
  void unsetImage(const std::string& name) {
    pipeline_->setImage(name, Image());
    inputs_.erase(name);
  }

  void setCamera(const Camera& camera) {
    pipeline_->setCamera(camera);
    camera_ = camera;
    committed_ = false;
  }

  // None (an empty pointer) turns the environment fill off.
  void setEnvironment(std::shared_ptr<const EnvironmentMap> environment) {
    static const EnvironmentMap none;  // the pipeline keeps a pointer: never a temporary
    pipeline_->setEnvironment(environment ? *environment : none);
    environment_ = std::move(environment);
    committed_ = false;
  }

  // `gbuffer` is kept alive here: the C++ pipeline reads it at execute().
  void setView(int index, std::shared_ptr<const GBuffer> gbuffer, const Camera& camera, const std::string& label,
               ViewTime time) {
    pipeline_->setView(index, *gbuffer, camera, label, time);  // validates the index first
    const View view{std::move(gbuffer), camera, label, time};
    if (index == static_cast<int>(views_.size())) views_.push_back(view);
    else views_[index] = view;
    committed_ = false;
  }

  void clearViews() {
    pipeline_->clearViews();
    views_.clear();
    committed_ = false;
  }

  int viewCount() const { return static_cast<int>(views_.size()); }

  TraceSettings& settings() { return settings_; }

  void commit() {
    leaveViews();
    pipeline_->settings() = settings_;
    pipeline_->commit();
    committed_ = true;
    committedInputs_ = inputs_;
  }

  void execute() {
    if (leaveViews() && committed_) {
      // The fresh pipeline committed as the old one was, then given the images set since: its
      // execute() accepts or refuses them as the old one's would.
      for (const auto& [name, input] : committedInputs_) pipeline_->setImage(name, input.view);
      pipeline_->settings() = settings_;
      pipeline_->commit();
      for (const auto& [name, input] : inputs_) pipeline_->setImage(name, input.view);
    }
    pipeline_->settings() = settings_;
    pipeline_->execute();
  }

  py::array output(const std::string& name) const {
    const Image& image = pipeline_->output(name);
    auto keeper = new std::shared_ptr<Pipeline>(pipeline_);
    py::capsule owner(keeper, [](void* p) { delete static_cast<std::shared_ptr<Pipeline>*>(p); });
    return arrayView(image, owner);
  }

  const Pipeline& pipeline() const { return *pipeline_; }

 private:
  // Returns true when views held the pipeline and a fresh one took its place.
  bool leaveViews() {
    if (pipeline_.use_count() == 1) return false;
    auto fresh = std::make_shared<Pipeline>(device_);
    for (const auto& [name, input] : inputs_) fresh->setImage(name, input.view);
    if (camera_) fresh->setCamera(*camera_);
    if (environment_) fresh->setEnvironment(*environment_);
    for (size_t k = 0; k < views_.size(); ++k)
      fresh->setView(static_cast<int>(k), *views_[k].gbuffer, views_[k].camera, views_[k].label, views_[k].time);
    pipeline_ = std::move(fresh);
    return true;
  }

  Device device_;
  std::shared_ptr<Pipeline> pipeline_;
  struct Input {
    ImageView view;
    std::shared_ptr<const void> keeper;
  };
  std::map<std::string, Input> inputs_, committedInputs_;  // the latter alive until the next commit
  std::optional<Camera> camera_;
  std::shared_ptr<const EnvironmentMap> environment_;
  struct View {
    std::shared_ptr<const GBuffer> gbuffer;
    Camera camera;
    std::string label;
    ViewTime time;
  };
  std::vector<View> views_;
  TraceSettings settings_;
  bool committed_ = false;
};

}  // namespace

void bindPipeline(py::module_& m) {
  py::class_<PythonPipeline>(m, "Pipeline",
                             "The SSR pipeline (include/ssrcl/pipeline.hpp): setImage/setFrame, setCamera, settings, "
                             "setView/clearViews, commit(), execute(), output('reflection' | 'distance' | 'view').")
      .def(py::init<const Device&>(), py::arg("device"))
      .def(
          "setImage",
          [](PythonPipeline& p, const std::string& name, const py::array& array) {
            auto held = std::shared_ptr<py::array>(new py::array(viewableArray(array, name.c_str())), [](py::array* a) {
              py::gil_scoped_acquire gil;  // the last owner may let go without the GIL
              delete a;
            });
            p.setImage(name, viewOfArray(*held, name.c_str()), held);
          },
          py::arg("name"), py::arg("image"),
          "An input as an HxWxC array (HxW for one channel): color (3 or 4), depth, normal, roughness, base, "
          "specular, f0 (3) or base_color (3) and metallic, back_depth. float32 and float16 arrays of any positive strides "
          "are read where they are (no copy) at commit() and execute(), so keep them unchanged until then; other "
          "dtypes and layouts are converted once.")
      .def(
          "setFrame",
          [](PythonPipeline& p, std::shared_ptr<Frame> frame) {
            // Shares the frame's pixels, no copy; a pass the frame lacks is unset, as Pipeline::setGBuffer
            // does, so a pipeline reused for the next frame keeps none of the previous frame's.
            for (const auto& [name, image] : pipelinePasses(frame->gbuffer))
              if (image->empty())
                p.unsetImage(name);
              else
                p.setImage(name, ImageView(image->data.data(), image->width, image->height, image->channels),
                           std::shared_ptr<const Image>(frame, image));
            p.setCamera(frame->camera);
          },
          py::arg("frame"), "Every pass of a loadFrame() result and its camera, as `ssrcl trace` sets them.")
      .def(
          "setView",
          [](PythonPipeline& p, int index, std::shared_ptr<Frame> frame, const std::string& label,
             bool otherTime) {
            p.setView(index, std::shared_ptr<const GBuffer>(frame, &frame->gbuffer), frame->camera, label,
                      otherTime ? ViewTime::Other : ViewTime::Same);
          },
          py::arg("index"), py::arg("frame"), py::arg("label") = "", py::arg("other_time") = false,
          "Auxiliary view `index` (0, 1, ...; viewCount() appends) from a loadFrame() result and its camera: rays "
          "the frame leaves unresolved continue in it (Pipeline::setView in include/ssrcl/pipeline.hpp). `label` "
          "names it in messages; other_time=True: a neighbouring frame, whose hits the frame shows have moved are "
          "not taken (ViewTime::Other).")
      .def(
          "setView",
          [](PythonPipeline& p, int index, const Camera& camera, const FloatArray& color, const FloatArray& depth,
             const FloatArray& normal, const std::optional<FloatArray>& roughness, const std::string& label,
             bool otherTime) {
            auto g = std::make_shared<GBuffer>();
            g->color = imageFromArray(color, "view color");
            g->depth = imageFromArray(depth, "view depth");
            g->normal = imageFromArray(normal, "view normal");
            if (roughness) g->roughness = imageFromArray(*roughness, "view roughness");
            p.setView(index, g, camera, label, otherTime ? ViewTime::Other : ViewTime::Same);
          },
          py::arg("index"), py::arg("camera"), py::arg("color"), py::arg("depth"), py::arg("normal"),
          py::arg("roughness") = py::none(), py::arg("label") = "", py::arg("other_time") = false,
          "Auxiliary view `index` from arrays as setImage takes them (colour, planar depth, world normals; no "
          "roughness: no glossy pixels), copied, with its own camera and size.")
      .def("clearViews", &PythonPipeline::clearViews)
      .def("viewCount", &PythonPipeline::viewCount)
      .def("setCamera", &PythonPipeline::setCamera, py::arg("camera"))
      .def("setEnvironment", &PythonPipeline::setEnvironment, py::arg("environment"),
           "Environment fill (an EnvironmentMap, or None to turn it off): the lobe share not found on screen "
           "takes the environment, settings.environmentRotation / environmentIntensity; A stays the screen fraction.")
      .def_property(
          "settings", [](PythonPipeline& p) -> TraceSettings& { return p.settings(); },
          [](PythonPipeline& p, const TraceSettings& s) { p.settings() = s; }, py::return_value_policy::reference_internal,
          "The TraceSettings used by the next commit() and execute(); change it in place or assign a new one.")
      .def("commit", &PythonPipeline::commit, py::call_guard<py::gil_scoped_release>(),
           "Validates the inputs and settings, compiles the kernels (once per device) and allocates.")
      .def("execute", &PythonPipeline::execute, py::call_guard<py::gil_scoped_release>())
      .def("output", &PythonPipeline::output, py::arg("name"),
           "'reflection' (HxWx4: premultiplied RGB, A = confidence), 'distance' (HxWx1) or, with views, 'view' "
           "(HxWx2: the source of most of the found weight, 0 the frame, k the view of index k-1, -1 none; the "
           "share of A found in views), as read-only arrays over the pipeline's buffers (no copy); later commits "
           "and executes leave them unchanged.")
      .def("stageTimes",
           [](const PythonPipeline& p) { return p.pipeline().stageTimes().ms; },
           "Device milliseconds per stage of the last execute().")
      .def("deviceBytes", [](const PythonPipeline& p) { return p.pipeline().deviceBytes(); });
}

}  // namespace ssrcl::python
