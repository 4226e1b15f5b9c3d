// The frame resource table (host/pipeline/frame_resources.hpp): stages bind the buffers they share
// from it by role, and only the roles they declare. A stage binding a role it did not declare, or
// writing one it declared only reading, fails at commit naming the stage and the role; so does a
// role two stages plan or none does. The stages' declarations must also fit together: every role a
// stage reads is written by some stage (here), and every stage of a pipeline in each configuration
// binds only what it declares (test_kernel_args, which commits them).
#include <gtest/gtest.h>

#include <functional>
#include <set>

#include "pipeline/back_pyramid_stage.hpp"
#include "pipeline/color_pyramid_stage.hpp"
#include "pipeline/environment_stage.hpp"
#include "pipeline/filter_stage.hpp"
#include "pipeline/frame_resources.hpp"
#include "pipeline/hzb_stage.hpp"
#include "pipeline/resolve_stage.hpp"
#include "pipeline/setup_stage.hpp"
#include "pipeline/thickness_stage.hpp"
#include "pipeline/trace_stage.hpp"
#include "pipeline/view_stage.hpp"
#include "support/test_device.hpp"

namespace {

using namespace ssrcl::detail;
using ssrcl::test::sharedTestDevice;

std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const ssrcl::Error& e) {
    EXPECT_EQ(e.code(), ssrcl::ErrorCode::InvalidOperation);
    return e.what();
  }
  return "";
}

struct Table {
  FrameResources resources;
  DeviceBuffers buffers;
  const StageAccess writer{"writer", {}, {Role::Positions, Role::Planes}};
  Table() {
    resources.beginPlan();
    resources.plan(writer, buffers, Role::Positions, 64);
    resources.plan(writer, buffers, Role::Planes, 64);
    buffers.allocate(ssrcl::detail::DeviceAccess::impl(sharedTestDevice()), "the test table");
  }
};

TEST(FrameResources, DeclaredRolesBind) {
  Table t;
  const StageAccess reader{"reader", {Role::Positions}, {Role::Planes}};
  EXPECT_EQ(refusal([&] { EXPECT_NE(t.resources.read(reader, Role::Positions)(), nullptr); }), "");
  EXPECT_EQ(refusal([&] { EXPECT_NE(t.resources.write(reader, Role::Planes)(), nullptr); }), "");
  EXPECT_EQ(refusal([&] { t.resources.read(reader, Role::Planes); }), "");  // a written role is bound too
}

TEST(FrameResources, AnUndeclaredRoleIsRefusedByName) {
  Table t;
  const StageAccess reader{"reader", {Role::Positions}, {}};
  EXPECT_EQ(refusal([&] { t.resources.read(reader, Role::Planes); }),
            "reader binds the frame's planes but does not declare it");
  EXPECT_EQ(refusal([&] { t.resources.write(reader, Role::Positions); }),
            "reader writes the frame's positions but does not declare writing it");
  EXPECT_EQ(refusal([&] { t.resources.plan(reader, t.buffers, Role::Normals, 64); }),
            "reader plans the frame's normals but does not declare it");
}

TEST(FrameResources, ARolePlannedTwiceOrByNoneIsRefused) {
  Table t;
  const StageAccess other{"other", {Role::Normals}, {Role::Positions}};
  EXPECT_EQ(refusal([&] { t.resources.plan(other, t.buffers, Role::Positions, 64); }),
            "the frame's positions is planned by both writer and other");
  EXPECT_EQ(refusal([&] { t.resources.read(other, Role::Normals); }),
            "other binds the frame's normals, which no stage planned");
  t.resources.beginPlan();  // a new plan: nothing planned yet
  EXPECT_EQ(refusal([&] { t.resources.read(other, Role::Positions); }),
            "other binds the frame's positions, which no stage planned");
}

// Every role a stage reads is written by a stage of the same frame (the main frame's or, for
// the views' trace in a view, the view's own stages).
TEST(FrameResources, EveryRoleReadIsWrittenBySomeStage) {
  const std::vector<const StageAccess*> main = {
      &SetupStage::access,        &ThicknessStage::access, &HzbStage::access,     &BackPyramidStage::access,
      &ColorPyramidStage::access, &TraceStage::access,     &ResolveStage::access, &FilterStage::access,
      &EnvironmentStage::access,  &ViewStage::access};
  const std::vector<const StageAccess*> view = {&SetupStage::access,        &ThicknessStage::access,
                                                &HzbStage::access,          &BackPyramidStage::access,
                                                &ColorPyramidStage::access, &ViewStage::viewAccess};
  for (const auto* frame : {&main, &view}) {
    std::set<Role> written;
    for (const StageAccess* a : *frame) written.insert(a->writes.begin(), a->writes.end());
    for (const StageAccess* a : *frame)
      for (Role r : a->reads) EXPECT_TRUE(written.count(r)) << a->stage << " reads " << roleName(r) << ", unwritten";
  }
}

}  // namespace
