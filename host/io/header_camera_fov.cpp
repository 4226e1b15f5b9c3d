// A header camera's field of view from outside the file, given or fitted to the world positions:
// Karma's headers hold the camera's pose and no projection (HeaderCamera::unprojected), and no
// field-of-view attribute either.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>
#include <vector>

#include "conventions.hpp"
#include "exr_header_camera.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl {
namespace {

std::string degrees(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

// Gives a pose-only header camera the projection of `fovDegrees`; `origin` says where it came from.
void complete(HeaderCamera& h, double fovDegrees, const std::string& origin) {
  const PixelBox display{0, 0, h.camera.width - 1, h.camera.height - 1};
  const double nearPlane = h.camera.nearPlane, farPlane = h.camera.farPlane;
  h.camera = detail::pinholeCamera(h.camera.view, fovDegrees, display, origin + ": the field of view");
  // The header's clip planes, read before the projection was known, still hold.
  if (h.clipPlanesKnown) setClipPlanes(h.camera, nearPlane, farPlane);
  h.unprojected.clear();
  h.attributes += " + " + origin;
}

// A pixel of the fit: where its position points, (x, y) / -z in eye space, and its centre, both
// in units of the focal length of x (NDC x, and NDC y times height / width), so that the model is
// centre = focal * direction on both axes.
struct Ray {
  glm::dvec2 direction, centre;
};

// Fewer pixels than this decide nothing; a pixel this near the axis (direction) says little.
constexpr size_t kMinPixels = 100;
constexpr double kNearAxis = 0.02;

}  // namespace

void applyFieldOfView(HeaderCamera& h, double fovDegrees, const std::string& file) {
  const std::string given = "--fov " + degrees(fovDegrees);
  if (!h.unprojected.empty()) return complete(h, fovDegrees, given);
  const std::string header = file + ": the header camera (" + h.attributes + ")";
  if (!detail::isPerspective(h.camera))
    throw Error(ErrorCode::InvalidInput,
                header + " is orthographic, which has no field of view: drop " + given + " or give --camera");
  // The header's own, measured as --fov is: across the display window, from the axis' focal length.
  const double own = 2.0 * std::atan(1.0 / h.camera.projection[0][0]) * 180.0 / M_PI;
  if (std::abs(own - fovDegrees) > 0.1)
    throw Error(ErrorCode::InvalidInput, header + " has a horizontal field of view of " + degrees(own) +
                                             " degrees but " + given + " says otherwise: drop --fov or correct it");
}

void fitFieldOfView(HeaderCamera& h, const GBuffer& g, const std::string& file) {
  const Image& p = g.position;
  const double width = g.displayWindow.width(), height = g.displayWindow.height();
  const std::string refused = file + ": the world positions do not fit the header camera's pose (" + h.attributes +
                              ") under any field of view: ";
  std::vector<Ray> rays;
  long long behind = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const float* v = &p.data[(size_t(y) * p.width + x) * 3];
      const glm::dvec3 world(v[0], v[1], v[2]);
      if (!detail::isSurfacePosition(world)) continue;
      const glm::dvec3 eye(h.camera.view * glm::dvec4(world, 1.0));
      if (!(eye.z < 0.0)) {
        ++behind;
        continue;
      }
      // The pixel centre in display-window coordinates, as NDC.
      const double px = g.dataWindow.minX - g.displayWindow.minX + x + 0.5;
      const double py = g.dataWindow.minY - g.displayWindow.minY + y + 0.5;
      rays.push_back({glm::dvec2(eye.x, eye.y) / -eye.z,
                      glm::dvec2(2.0 * px / width - 1.0, (1.0 - 2.0 * py / height) * height / width)});
    }
  if (rays.size() < kMinPixels || behind > (long long)rays.size())
    throw Error(ErrorCode::InvalidInput, refused + std::to_string(behind) + " of " +
                                             std::to_string(behind + (long long)rays.size()) +
                                             " lie behind it; give --camera (or check --fov's file)");
  // A first focal length robust to outliers: the median of each off-axis pixel's own.
  std::vector<double> own;
  for (const Ray& r : rays)
    if (glm::length(r.direction) > kNearAxis)
      own.push_back(glm::dot(r.centre, r.direction) / glm::dot(r.direction, r.direction));
  if (own.size() < kMinPixels)
    throw Error(ErrorCode::InvalidInput, refused + "too few of them off the camera's axis; give --fov or --camera");
  double focal = detail::median(own);
  const double pixelsPerUnit = width / 2.0;  // of the focal-length units above, on both axes
  const auto residuals = [&](double f) {
    std::vector<double> r;
    for (const Ray& ray : rays) r.push_back(glm::length(ray.centre - f * ray.direction) * pixelsPerUnit);
    return r;
  };
  // Least squares over the pixels within a pixel (or three median residuals) of the first fit.
  std::vector<double> r = residuals(focal);
  const double keep = std::max(1.0, 3.0 * detail::median(r));
  double along = 0.0, norm = 0.0;
  for (size_t i = 0; i < rays.size(); ++i)
    if (r[i] <= keep) along += glm::dot(rays[i].centre, rays[i].direction), norm += glm::dot(rays[i].direction, rays[i].direction);
  if (norm > 0.0) focal = along / norm;
  const double off = detail::median(residuals(focal));
  if (!(focal > 0.0) || !(off <= 0.5))
    throw Error(ErrorCode::InvalidInput, refused + "at best half of them land more than " + degrees(off) +
                                             " pixels from their own; give --camera, or --fov if the pose is right");
  const double fov = 2.0 * std::atan(1.0 / focal) * 180.0 / M_PI;
  complete(h, fov, "field of view " + degrees(fov) + " degrees fitted to the positions (median " + degrees(off) + " px off)");
}

}  // namespace ssrcl
