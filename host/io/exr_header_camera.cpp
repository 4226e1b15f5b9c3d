// Cameras stored in EXR headers by renderers, turned into ssrcl's (OpenGL eye space and clip
// matrix over the display window). docs/renderers.md, "Header cameras", lists the attributes and their sources.
#include "exr_header_camera.hpp"

#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfMatrixAttribute.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>

#include "conventions.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl::detail {

Camera pinholeCamera(const glm::dmat4& view, double fovDegrees, const PixelBox& display, const std::string& where) {
  if (!(fovDegrees > 0.0 && fovDegrees < 180.0))
    throw Error(ErrorCode::InvalidInput, where + " must be in (0, 180) degrees");
  const double focal = 1.0 / std::tan(fovDegrees * M_PI / 360.0);
  Camera camera;
  camera.view = view;
  camera.projection = glm::dmat4(0.0);
  camera.projection[0][0] = focal;
  camera.projection[1][1] = focal * display.width() / display.height();
  camera.projection[2][3] = -1.0;
  camera.width = display.width();
  camera.height = display.height();
  setClipPlanes(camera, 1.0, INFINITY);  // until fitClipPlanes or the header's planes set them
  return camera;
}

namespace {

// A field of view spans the display window's width; its height follows from the pixel counts only
// for square pixels. Anamorphic renders would come out stretched: refused instead.
void requireSquarePixels(const Imf::Header& header, const std::string& path, const std::string& camera) {
  if (std::abs(header.pixelAspectRatio() - 1.0f) > 1e-6f)
    throw Error(ErrorCode::InvalidInput, path + ": pixelAspectRatio is " + std::to_string(header.pixelAspectRatio()) +
                                             ": the " + camera + " is read for square pixels only; give --camera");
}

// Imath matrices multiply row vectors (p' = p M, m[row][col]); the same numbers read as GLM's
// m[column][row] are the column-vector matrix of the same map, so entries copy across as is.
glm::dmat4 fromImath(const Imath::M44f& m) {
  glm::dmat4 g;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) g[i][j] = m[i][j];
  return g;
}

Imath::M44f toImath(const glm::dmat4& g) {
  Imath::M44f m;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m[i][j] = float(g[i][j]);
  return m;
}

const Imath::M44f* matrix(const Imf::Header& header, const char* name) {
  const auto* a = header.findTypedAttribute<Imf::M44fAttribute>(name);
  return a ? &a->value() : nullptr;
}

template <class Attribute>
std::optional<double> number(const Imf::Header& header, const char* name) {
  const auto* a = header.findTypedAttribute<Attribute>(name);
  return a ? std::optional<double>(a->value()) : std::nullopt;
}

// OpenEXR camera space (+z forward, left-handed) to OpenGL eye space (-z forward).
const glm::dmat4 kFlipZ(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1);

// Builds a clip matrix from rows x, y, w of a map from eye space to homogeneous NDC x and y in
// [-1, 1] (y up): w must be a multiple of -z (perspective) or of 1 (orthographic). The depth row
// is a placeholder (near 1, far infinity) until fitClipPlanes or the header's clip planes set it.
Camera fromEyeToNdc(const glm::dmat4& eyeToNdc, const glm::dmat4& view, const PixelBox& display,
                    const std::string& where) {
  const glm::dvec4 w(eyeToNdc[0][3], eyeToNdc[1][3], eyeToNdc[2][3], eyeToNdc[3][3]);
  const double scale = glm::length(w);
  const bool perspective = std::abs(w.z) > 1e-6 * scale;
  const double k = perspective ? -w.z : w.w;
  if (!(scale > 0.0) || std::abs(w.x) > 1e-5 * scale || std::abs(w.y) > 1e-5 * scale ||
      (perspective && std::abs(w.w) > 1e-5 * scale) || !(k > 0.0))
    throw Error(ErrorCode::InvalidInput,
                where + " is not the projection of a pinhole or orthographic camera looking along its z axis");
  glm::dmat4 p(0.0);
  for (int c = 0; c < 4; ++c) {
    p[c][0] = eyeToNdc[c][0] / k;
    p[c][1] = eyeToNdc[c][1] / k;
  }
  if (perspective) {
    p[2][3] = -1.0;
  } else {
    p[3][3] = 1.0;
  }
  Camera camera;
  camera.view = view;
  camera.projection = p;
  camera.width = display.width();
  camera.height = display.height();
  camera.nearPlane = 1.0;
  camera.farPlane = INFINITY;
  setClipPlanes(camera, camera.nearPlane, camera.farPlane);
  return camera;
}

// worldToCamera with worldToNDC (or worldToScreen). Renderers disagree on both, so each is told
// from the matrices themselves rather than from the attribute's name:
// - the projected space: OpenEXR's NDC ((0,0) top-left, (1,1) bottom-right of the display window)
//   has y down; screen space as OpenImageIO defines it ("worldtoscreen", src/doc/stdmetadata.rst:
//   x and y in [-1, 1] over the display window) has y up. OIIO wrote that screen matrix under the
//   name worldToNDC before 2.2 (commit fed34425b), so Arnold 4.2's files carry it so
//   (github.com/zewt/exrflatten, sample/sample2.exr: P lands on its pixels only when read so), as
//   do Houdini's (a Mantra file's oiiotool dump in github.com/ynput/ayon-houdini/issues/76).
// - the camera space: OpenEXR's looks down +z (Arnold's file too); Houdini's looks down -z (the
//   same dump: its worldToNDC's w is minus its camera z). A perspective projection's w tells
//   them apart; an orthographic one's cannot: both readings are kept (HeaderCamera::reversed)
//   for orientHeaderCamera to choose from the passes.
// The z the files hold is discarded.
std::optional<HeaderCamera> standardCamera(const Imf::Header& header, const Imath::M44f& toCamera,
                                           const PixelBox& display, const std::string& path) {
  const Imath::M44f* toNdc = matrix(header, "worldToNDC");
  const Imath::M44f* projected = toNdc ? toNdc : matrix(header, "worldToScreen");
  if (!projected) return std::nullopt;
  const glm::dmat4 fileCamera = fromImath(toCamera);
  const glm::dmat4 cameraToProjected = fromImath(*projected) * glm::inverse(fileCamera);
  const std::string name = toNdc ? "worldToNDC" : "worldToScreen";
  // Karma (Houdini Solaris, CPU and XPU, 2025) writes worldToNDC as a copy of worldToCamera
  // (github.com/EmilDohne/cryptomatte-api, test/images/karma_*_solaris_*.exr): no projection, which
  // would read as an orthographic camera two units wide.
  double offIdentity = 0.0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) offIdentity = std::max(offIdentity, std::abs(cameraToProjected[c][r] - (c == r)));
  if (offIdentity < 1e-5) {
    requireSquarePixels(header, path, "camera completed by a field of view");
    // The pose alone, in OpenEXR's camera space (+z forward: the file's scene lies on that side);
    // a field of view completes it (applyFieldOfView, fitFieldOfView).
    HeaderCamera h;
    h.camera = pinholeCamera(kFlipZ * fileCamera, 90.0, display, "placeholder");
    h.attributes = "worldToCamera";
    h.unprojected = path + ": header attribute '" + name +
                    "' is the same matrix as 'worldToCamera': it holds no projection (as Karma writes it); give "
                    "--fov (the camera's horizontal field of view) or --camera";
    return h;
  }
  const bool lookingDownMinusZ = cameraToProjected[2][3] < 0.0;  // w = -z: Houdini's camera space
  const glm::dvec4 w(cameraToProjected[0][3], cameraToProjected[1][3], cameraToProjected[2][3],
                     cameraToProjected[3][3]);
  const bool orthographic = std::abs(w.z) <= 1e-6 * glm::length(w);  // w constant: no divide to tell by
  const bool yUp = cameraToProjected[1][1] > 0.0;                // camera y up is projected y up: screen space
  glm::dmat4 toUnit(1.0);  // from the file's projected space to our NDC, y up: screen space already is
  if (!yUp) {
    toUnit[0][0] = 2.0, toUnit[3][0] = -1.0;  // x' = 2x - w
    toUnit[1][1] = -2.0, toUnit[3][1] = 1.0;  // y' = w - 2y
  }
  const auto reading = [&](const glm::dmat4& view) {
    return fromEyeToNdc(toUnit * fromImath(*projected) * glm::inverse(view), view, display,
                        path + ": header attribute '" + name + "'");
  };
  HeaderCamera h;
  h.camera = reading(lookingDownMinusZ ? fileCamera : kFlipZ * fileCamera);
  if (orthographic) h.reversed = reading(fileCamera);
  h.attributes = "worldToCamera" + std::string(lookingDownMinusZ ? " (-z forward)" : "") + " + " + name +
                 (yUp ? " (screen space)" : "");
  return h;
}

// V-Ray's camera frame in cameraTransform: x right, looking down -y, -z up (a quarter turn about
// x from OpenGL's eye space). Columns: where eye x, y, z, w go.
const glm::dmat4 kEyeToVray(1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1);

// V-Ray: cameraTransform is camera-to-world in the frame above, cameraFov the horizontal field of
// view in degrees. Both from V-Ray files: a V-Ray for Maya 3.6 header (Psyop/Cryptomatte
// sample_images/cornellBox_CryptoWildcard.0001.exr: rows (1 0 0, 0 0 1, 0 -1 0), translation
// (0 5 20), i.e. Maya's default front view at (0, 5, 20) looking down world -z with y up; cameraFov
// 54.4322 = 2 atan(cameraAperture 36 / (2 cameraFocalLength 35))), and a V-Ray 3.6 render whose
// world-position pass lies 100% in front of the camera read so and lands on its pixels near the
// frame's centre (tests/test_conventions.cpp, VrayFileHeaderCamera). Row- or column-vector storage
// is told apart by where the translation sits.
std::optional<HeaderCamera> vrayCamera(const Imf::Header& header, const PixelBox& display, const std::string& path) {
  const Imath::M44f* transform = matrix(header, "cameraTransform");
  const std::optional<double> fov = number<Imf::FloatAttribute>(header, "cameraFov");
  if (!transform || !fov) return std::nullopt;
  glm::dmat4 vrayToWorld = fromImath(*transform);
  const bool columnStored = (*transform)[3][0] == 0.f && (*transform)[3][1] == 0.f && (*transform)[3][2] == 0.f &&
                            ((*transform)[0][3] != 0.f || (*transform)[1][3] != 0.f || (*transform)[2][3] != 0.f);
  if (columnStored) vrayToWorld = glm::transpose(vrayToWorld);
  const glm::dmat4 cameraToWorld = vrayToWorld * kEyeToVray;
  // An int in V-Ray's own files; a float once a compositor has rewritten the header (V-Ray 3.6
  // passes saved by Fusion).
  std::optional<double> projection = number<Imf::IntAttribute>(header, "cameraProjection");
  if (!projection) projection = number<Imf::FloatAttribute>(header, "cameraProjection");
  if (projection && *projection != 0) {
    char value[32];
    std::snprintf(value, sizeof value, "%g", *projection);
    throw Error(ErrorCode::InvalidInput, path + ": header attribute 'cameraProjection' is " + value +
                                             ", not 0 (perspective), the only V-Ray projection read; give --camera");
  }
  requireSquarePixels(header, path, "V-Ray camera (cameraFov)");
  HeaderCamera h;
  h.camera = pinholeCamera(glm::inverse(cameraToWorld), *fov, display, path + ": header attribute 'cameraFov'");
  h.attributes = "cameraTransform + cameraFov";
  return h;
}

// Clip planes, where the header has them (the projection matrices discard z): RenderMan's
// (ILM's PRMan OpenEXR driver writes RiClipping's near and far as clipNear/clipFar), Arnold's
// (arnold/camera/near_clip and far_clip, in Arnold 4.2's files) and V-Ray's. A pair that is not
// a range (V-Ray files in the wild carry cameraNearClip 0) leaves them to fitClipPlanes. Far
// planes from 1e10 on (RenderMan's default is 1e38, Arnold's 1e30) are infinity: depth there
// means no surface.
void readClipPlanes(const Imf::Header& header, HeaderCamera& h) {
  static const char* const pairs[][2] = {{"clipNear", "clipFar"},
                                         {"arnold/camera/near_clip", "arnold/camera/far_clip"},
                                         {"cameraNearClip", "cameraFarClip"}};
  for (const auto& [nearName, farName] : pairs) {
    const std::optional<double> n = number<Imf::FloatAttribute>(header, nearName);
    const std::optional<double> f = number<Imf::FloatAttribute>(header, farName);
    if (n && f && *n > 0.0 && *f > *n) {
      // An orthographic depth row has no infinite form (1e10 squeezes every depth into float
      // rounding): with an infinite far plane fitClipPlanes sets both from the depth.
      const double farPlane = *f < 1e10 ? *f : INFINITY;
      if (std::isinf(farPlane) && !detail::isPerspective(h.camera)) return;
      setClipPlanes(h.camera, *n, farPlane);
      if (h.reversed) setClipPlanes(*h.reversed, *n, farPlane);
      h.clipPlanesKnown = true;
      h.attributes += std::string(", ") + nearName + " + " + farName;
      return;
    }
  }
}

std::optional<HeaderCamera> readCamera(const Imf::Header& header, const std::string& path) {
  const Imath::Box2i& d = header.displayWindow();
  const PixelBox display{d.min.x, d.min.y, d.max.x, d.max.y};
  std::optional<HeaderCamera> h;
  if (const Imath::M44f* toCamera = matrix(header, "worldToCamera"))
    h = standardCamera(header, *toCamera, display, path);
  if (!h) h = vrayCamera(header, display, path);
  if (!h) return h;
  readClipPlanes(header, *h);
  validateCamera(h->camera, (path + ": header camera (" + h->attributes + ")").c_str());
  return h;
}

// Our clip space to OpenEXR's NDC: x' = (x + w) / 2, y' = (w - y) / 2 (y down), z' = (z + w) / 2.
const glm::dmat4 kClipToNdc(0.5, 0, 0, 0, 0, -0.5, 0, 0, 0, 0, 0.5, 0, 0.5, 0.5, 0.5, 1);

}  // namespace

void cameraToHeader(const Camera& camera, Imf::Header& header) {
  header.insert("worldToCamera", Imf::M44fAttribute(toImath(kFlipZ * camera.view)));
  header.insert("worldToNDC", Imf::M44fAttribute(toImath(kClipToNdc * camera.projection * camera.view)));
}

std::optional<HeaderCamera> cameraFromHeader(const Imf::Header& header, const std::string& path) {
  try {
    return readCamera(header, path);
  } catch (const Error& e) {
    HeaderCamera unusable;
    unusable.problem = e.what();
    return unusable;
  }
}

}  // namespace ssrcl::detail
