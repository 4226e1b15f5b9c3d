// The stages' argument bindings against the kernels: each bindArgs names the parameters it binds
// (host/pipeline/stage_support.hpp), checked against the kernel's own (built with
// -cl-kernel-arg-info). A binding out of step with its kernel must fail at commit, naming both,
// and every stage of each configuration (views, environment, denoise, prefilter) must agree.
#include <gtest/gtest.h>

#include "pipeline/device_impl.hpp"
#include "pipeline/stage_support.hpp"
#include "scenes/analytic_scene.hpp"
#include "ssrcl/ssrcl.hpp"
#include "support/test_device.hpp"

namespace {

using ssrcl::detail::checkKernelArgs;
using ssrcl::test::sharedTestDevice;

cl::Kernel hzbKernel() {
  ssrcl::Device::Impl& d = ssrcl::detail::DeviceAccess::impl(sharedTestDevice());
  return cl::Kernel(d.program({"ssrcl_shared.h", "common.cl", "hzb.cl"}), "depth_reduce");
}

std::string refusal(const cl::Kernel& kernel, cl_uint first, const char* names, size_t count) {
  try {
    checkKernelArgs(kernel, first, names, count);
  } catch (const ssrcl::Error& e) {
    EXPECT_EQ(e.code(), ssrcl::ErrorCode::InvalidOperation);
    return e.what();
  }
  return "";
}

TEST(KernelArgs, TheKernelsOwnNamesPass) {
  const cl::Kernel k = hzbKernel();  // depth_reduce(pyramid, levels, dst_level)
  EXPECT_EQ(refusal(k, 0, "pyramid, levels, dst_level", 3), "");
  EXPECT_EQ(refusal(k, 1, "levels", 1), "");
}

TEST(KernelArgs, SwappedMissingOrExtraArgumentsAreRefusedByName) {
  const cl::Kernel k = hzbKernel();
  EXPECT_EQ(refusal(k, 0, "levels, pyramid", 2),
            "kernel depth_reduce: argument 0 is 'pyramid' but the host binds 'levels' there");
  EXPECT_EQ(refusal(k, 0, "pyramid, levels, dst_level, extra", 4),
            "kernel depth_reduce takes 3 arguments, the host binds 4");
  EXPECT_EQ(refusal(k, 0, "pyramid, levels", 3), "kernel depth_reduce: the host binds 3 arguments but names 2");
}

// A per-frame argument is found by its name in the list its stage binds: the index the kernel
// declares it at, and a name the list lacks refused, not set at some other index.
TEST(KernelArgs, AnArgumentIsFoundByItsNameInTheBoundList) {
  const ssrcl::detail::KernelArgList list{1, "levels, dst_level"};
  const cl::Kernel k = hzbKernel();
  EXPECT_EQ(refusal(k, list.first, list.names, 2), "");
  EXPECT_EQ(list["levels"], 1u);
  EXPECT_EQ(list["dst_level"], 2u);
  try {
    (void)list["pyramid"];
    ADD_FAILURE() << "an argument the list does not name was given an index";
  } catch (const ssrcl::Error& e) {
    EXPECT_EQ(e.code(), ssrcl::ErrorCode::InvalidOperation);
    EXPECT_STREQ(e.what(), "no kernel argument 'pyramid' among levels, dst_level");
  }
}

// Every stage binds through the check, and from the frame resource table only the roles it
// declares (host/pipeline/frame_resources.hpp): each configuration binds a different set (the
// filter's input or the outputs, hit counts, views, the environment), and every one commits and
// traces.
TEST(KernelArgs, EveryStageOfEachConfigurationAgreesWithItsKernels) {
  const ssrcl::test::Scene scene = ssrcl::test::makeScene("spheres_on_mirror");
  const ssrcl::Camera camera = ssrcl::test::makeCamera(scene.view, 64, 36);
  const ssrcl::test::AnalyticGBuffer gbuffer = ssrcl::test::renderGBuffer(scene, camera);
  ssrcl::Image sky(16, 8, 3);
  sky.data.assign(sky.data.size(), 0.5f);
  const ssrcl::EnvironmentMap env = ssrcl::prefilterEnvironment(sky);
  for (const char* preset : {"draft", "medium", "high"})  // high: denoise, prefilter, adaptive thickness
    for (bool extras : {false, true}) {
      SCOPED_TRACE(std::string(preset) + (extras ? " with a view and an environment" : ""));
      ssrcl::Pipeline p(sharedTestDevice());
      p.setGBuffer(gbuffer);
      p.setCamera(camera);
      if (extras) {
        p.setView(0, gbuffer, camera, "itself");
        p.setEnvironment(env);
      }
      p.settings() = ssrcl::qualityPreset(preset);
      EXPECT_NO_THROW({
        p.commit();
        p.execute();
      });
    }
}

}  // namespace
