#pragma once
// The frame's device buffers that stages share, one per role, owned by the pipeline (and by each
// auxiliary view for its own frame). A stage declares the roles it reads and writes and binds
// from the table only: no stage reaches into another's buffers, and binding a role a stage did
// not declare fails at commit, naming both.
#include <array>
#include <string>
#include <vector>

#include "stage_support.hpp"

namespace ssrcl::detail {

enum class Role {
  Positions,         // view-space point, planar depth in w (SSRCL_NO_SURFACE: none)
  Normals,           // view-space normal, roughness in w
  FillNormals,       // as Normals, for the environment fill (a mixed pixel: its surface's; setup.cl)
  Planes,            // surface plane over thickness, the trace's hit test (kernels/surface_plane.cl)
  BackGuess,         // with a back-face pass: the model's thickness over the exact one where it knows (else 0)
  PixelRays,         // rays per pixel
  RayList,           // the listed pixels
  TileList,          // the listed tiles
  DepthPyramid,      // the HZB, every level packed, level 0 at offset 0
  PyramidLevels,     // HzbLevel per level, of all three pyramids
  BackPyramid,       // per texel (nearest depth, farthest hit depth), levels as the HZB's (back_pyramid.cl)
  ColorPyramid,      // (rgb * hits, hits) per texel, levels as the HZB's; level 0 (rgb, hits)
  RayHits,           // per (pixel, batch slot); see kernels/trace.cl
  RayRadiance,       // per (pixel, batch slot)
  RayStates,         // per (pixel, batch slot), with views (SSRCL_RAY_*)
  ResolvedRgba,      // the resolve's sums (w c L, w c), finalized in place when the filter follows
  ResolvedDistance,  //   (its input)
  Reflection,        // the outputs
  Distance,
  ViewShare,         // source view and share per pixel, with views
  Count
};
const char* roleName(Role role);

// What a stage declares: its name (in messages) and the roles it reads and writes.
struct StageAccess {
  const char* stage;
  std::vector<Role> reads, writes;
};

class FrameResources {
 public:
  // Starts a plan: every shared role is planned by one stage, once.
  void beginPlan();
  // Plans `role` in `buffers` for `access`'s stage, which must declare it.
  void plan(const StageAccess& access, DeviceBuffers& buffers, Role role, size_t bytes,
            cl_mem_flags flags = CL_MEM_READ_WRITE);
  // The role's buffer for binding: one `access` declares it reads or writes, and some stage planned.
  // Throw Error(InvalidOperation) naming the stage and the role otherwise.
  const cl::Buffer& read(const StageAccess& access, Role role) const;
  const cl::Buffer& write(const StageAccess& access, Role role) const;  // declared as written

 private:
  const cl::Buffer& planned(const StageAccess& access, Role role) const;
  static constexpr size_t kRoles = size_t(Role::Count);
  std::array<cl::Buffer, kRoles> buffers_;   // stable addresses: DeviceBuffers keeps pointers
  std::array<const char*, kRoles> planner_{};  // the stage that planned each role this plan
};

}  // namespace ssrcl::detail
