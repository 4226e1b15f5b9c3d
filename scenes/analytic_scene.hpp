#pragma once
// Analytic scenes, exact ray-traced G-buffers and reflections in double precision: the generated
// inputs of `ssrcl bench` and the truth of the tests.
//
// Conventions: world up is +Y (glm::lookAt's default), so floors are planes y = const.
// The camera follows ssrcl/camera.hpp: pixel (x, y) centre is (x + 0.5, y + 0.5), y = 0 the top
// row, NDC x = 2 * sx / W - 1, NDC y = 1 - 2 * sy / H for continuous pixel coordinates (sx, sy).
// The sky (no hit) has depth kSkyDepth (Blender's convention), a zero normal and roughness 0.
#include <cstddef>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "ssrcl/camera.hpp"
#include "ssrcl/image.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl::scenes {

inline constexpr double kSkyDepth = 1e10;

// Colour = base * pattern(world position), pattern = 0.6 + 0.2 sin(k1.p + a_c) + 0.2 sin(k2.p + b_c)
// with |k1| = |k2| = 2 pi / period and per-channel phases: smooth at pixel scale, yet a hit a few
// pixels off the true point reads a different colour. See colorAt(). Untextured: colour = base
// everywhere (a constant-radiance emitter for glossy truth).
struct Material {
  glm::dvec3 base{0.8};
  double roughness = 0.0;
  double period = 1.0;  // world units; ~25-50 pixels on the presets' objects at 480x270
  bool textured = true;
};

struct Primitive {
  enum class Kind { Plane, Rectangle, Disk, Sphere, Box };
  Kind kind = Kind::Sphere;
  std::string name;
  glm::dvec3 center{0.0};      // plane: any point on it
  glm::dvec3 normal{0, 1, 0};  // plane, rectangle, disk (unit); two-sided
  glm::dvec3 halfSize{0.0};    // box: half extents; rectangle: x, z = half extents along u, v
  double radius = 0.0;         // sphere, disk
  double yawRadians = 0.0;     // box: rotation about +Y
  Material material;
};
// Rectangle/disk in-plane axes: u = normalize(cross(normal, +Z)) (or +X when normal ~ Z),
// v = cross(u, normal); for a floor (normal +Y) u = +X and v = +Z.
void planeAxes(const glm::dvec3& normal, glm::dvec3& u, glm::dvec3& v);

Primitive plane(const std::string& name, glm::dvec3 point, glm::dvec3 normal, Material m);
Primitive rectangle(const std::string& name, glm::dvec3 center, glm::dvec3 normal, double halfU, double halfV,
                    Material m);
Primitive disk(const std::string& name, glm::dvec3 center, glm::dvec3 normal, double radius, Material m);
Primitive sphere(const std::string& name, glm::dvec3 center, double radius, Material m);
Primitive box(const std::string& name, glm::dvec3 center, glm::dvec3 halfSize, double yawDegrees, Material m);

// Pinhole camera placement; combined with a resolution by makeCamera().
struct ViewParams {
  glm::dvec3 eye{0, 2, 8};
  glm::dvec3 target{0.0};
  glm::dvec3 up{0, 1, 0};
  double fovYDegrees = 45.0;
  double nearPlane = 0.1;
  double farPlane = 1000.0;
};

struct Scene {
  std::string name;
  std::vector<Primitive> primitives;
  glm::dvec3 skyColor{0.55, 0.7, 0.95};
  ViewParams view;  // the preset's suggested camera
};

// Presets (throw std::invalid_argument for unknown names):
//   "spheres_on_mirror"  mirror floor (16x16 rectangle at y = 0), 5 spheres and 2 boxes, camera
//                        looking down ~25 degrees; sky above the floor's far edge, a sphere
//                        straddling the left border, a yellow one near the bottom edge.
//   "mirror_wall"        mirror floor plus a vertical mirror wall (thin box) on the left, turned
//                        20 degrees toward the camera so it reflects 4 boxes and 2 spheres; camera
//                        looking down ~17 degrees.
//   "half_sky"           spheres_on_mirror seen level from low: the sky fills the top half.
// Every surface has roughness 0.
Scene makeScene(const std::string& name);
std::vector<std::string> sceneNames();

// glm::perspective / glm::lookAt in double; nearPlane/farPlane filled in.
Camera makeCamera(const ViewParams& view, int width, int height);

struct Ray {
  glm::dvec3 origin{0.0};
  glm::dvec3 direction{0, 0, -1};  // unit
};

struct Hit {
  int primitive = -1;  // index into Scene::primitives; -1 = no hit
  double t = 0.0;      // ray parameter (= distance, directions are unit)
  glm::dvec3 position{0.0};
  glm::dvec3 normal{0.0};  // unit; outward for closed shapes, facing the ray for planar ones
  explicit operator bool() const { return primitive >= 0; }
};

// Ray through continuous pixel coordinates (sx, sy), unprojected through inverse(P * V); starts on
// the near plane.
Ray primaryRay(const Camera& camera, double sx, double sy);
// Nearest hit with t > tMin; primitive == -1 when the ray escapes.
Hit intersect(const Scene& scene, const Ray& ray, double tMin = 0.0);
glm::dvec3 colorAt(const Scene& scene, const Hit& hit);  // sky colour for no hit
// Pixel x, y (continuous) and planar depth of a world point; w <= 0 (behind the eye) gives depth <= 0.
glm::dvec3 projectToScreen(const Camera& camera, const glm::dvec3& world);
double planarDepth(const Camera& camera, const glm::dvec3& world);

// The G-buffer images plus the exact primary hit of every pixel centre (row-major, y = 0 top).
struct AnalyticGBuffer : GBuffer {
  int width = 0, height = 0;
  std::vector<Hit> hits;
  const Hit& hit(int x, int y) const { return hits[std::size_t(y) * width + x]; }
};
AnalyticGBuffer renderGBuffer(const Scene& scene, const Camera& camera);

enum class ReflectionClass {
  NoSurface,  // the pixel shows the sky: no reflection is defined
  Visible,    // the reflected hit is on screen, in front of the near plane and seen by the camera
  OffScreen,  // the reflected hit projects outside the screen, behind the eye or beyond near/far
  Occluded,   // the reflected hit is on screen but another surface (or its own back) hides it
  Sky,        // the reflected ray escapes
};
const char* className(ReflectionClass c);

struct MirrorSample {
  ReflectionClass cls = ReflectionClass::NoSurface;
  Ray reflected;           // from the exact surface point along the exact mirror direction
  Hit hit;                 // first surface along `reflected`; hit.t = hit distance
  glm::dvec3 color{0.0};   // exact colour at hit.position (sky colour for Sky)
  glm::dvec3 screen{0.0};  // projectToScreen(hit.position) when there is a hit
  // Visible only: how much the answer changes within one pixel of `screen`, from the primary rays
  // at +-1 px (8 neighbours), i.e. what a screen-space tracer with one pixel of error may return.
  bool nearEdge = false;        // a neighbour sees another primitive or the sky
  double colorSpread = 0.0;     // largest max-abs colour difference to a neighbour
  double distanceSpread = 0.0;  // largest relative change of the distance from reflected.origin
};

// Mirror reflection of one surface point seen along unit `viewDir` (eye -> point).
MirrorSample reflectAt(const Scene& scene, const Camera& camera, const Hit& surface, const glm::dvec3& viewDir);

struct MirrorTruth {
  int width = 0, height = 0;
  std::vector<MirrorSample> samples;
  const MirrorSample& at(int x, int y) const { return samples[std::size_t(y) * width + x]; }
  std::size_t count(ReflectionClass c) const;
};
// reflectAt() for every pixel of `gbuffer` (rendered from the same scene and camera).
MirrorTruth exactMirrorReflection(const Scene& scene, const Camera& camera, const AnalyticGBuffer& gbuffer);

}  // namespace ssrcl::scenes

// The tests reach the scenes among their other helpers in ssrcl::test.
namespace ssrcl::test {
using namespace ssrcl::scenes;
}  // namespace ssrcl::test
