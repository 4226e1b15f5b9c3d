#include "scenes/analytic_scene.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <limits>
#include <stdexcept>

namespace ssrcl::scenes {
namespace {

using glm::dvec3;
using glm::dvec4;
constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

dvec3 rotateY(const dvec3& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z};
}

// Smallest root of |o + t d - c|^2 = r^2 above tMin (d unit), in the stable form.
double sphereT(const Primitive& s, const Ray& ray, double tMin) {
  const dvec3 oc = ray.origin - s.center;
  const double b = glm::dot(oc, ray.direction);
  // c - b^2 computed as |oc - b d|^2 keeps precision when the sphere is far away.
  const dvec3 perp = oc - b * ray.direction;
  const double disc = s.radius * s.radius - glm::dot(perp, perp);
  if (disc < 0) return kInf;
  const double q = std::sqrt(disc);
  if (-b - q > tMin) return -b - q;
  if (-b + q > tMin) return -b + q;
  return kInf;
}

double planarT(const Primitive& p, const Ray& ray, double tMin) {
  const double denom = glm::dot(ray.direction, p.normal);
  if (denom == 0) return kInf;
  const double t = glm::dot(p.center - ray.origin, p.normal) / denom;
  if (!(t > tMin)) return kInf;
  const dvec3 d = ray.origin + t * ray.direction - p.center;
  if (p.kind == Primitive::Kind::Disk) return glm::dot(d, d) <= p.radius * p.radius ? t : kInf;
  if (p.kind == Primitive::Kind::Rectangle) {
    dvec3 u, v;
    planeAxes(p.normal, u, v);
    return std::abs(glm::dot(d, u)) <= p.halfSize.x && std::abs(glm::dot(d, v)) <= p.halfSize.z ? t : kInf;
  }
  return t;
}

// Slab test in the box's local frame; `normal` gets the outward normal (local) of the face hit.
double boxT(const Primitive& b, const Ray& ray, double tMin, dvec3& localNormal) {
  const dvec3 o = rotateY(ray.origin - b.center, -b.yawRadians);
  const dvec3 d = rotateY(ray.direction, -b.yawRadians);
  double tNear = -kInf, tFar = kInf;
  int nearAxis = -1, farAxis = -1;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (std::abs(o[a]) > b.halfSize[a]) return kInf;
      continue;
    }
    double t0 = (-b.halfSize[a] - o[a]) / d[a], t1 = (b.halfSize[a] - o[a]) / d[a];
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > tNear) tNear = t0, nearAxis = a;
    if (t1 < tFar) tFar = t1, farAxis = a;
  }
  if (tNear > tFar) return kInf;
  const double t = tNear > tMin ? tNear : tFar;
  const int axis = tNear > tMin ? nearAxis : farAxis;
  if (!(t > tMin) || axis < 0) return kInf;
  localNormal = dvec3(0.0);
  localNormal[axis] = (o[axis] + t * d[axis]) > 0 ? 1.0 : -1.0;
  return t;
}

}  // namespace

void planeAxes(const dvec3& n, dvec3& u, dvec3& v) {
  dvec3 c = glm::cross(n, dvec3(0, 0, 1));
  if (glm::length(c) < 1e-6) c = glm::cross(n, dvec3(1, 0, 0));
  u = glm::normalize(c);
  v = glm::cross(u, n);
}

Primitive plane(const std::string& name, dvec3 point, dvec3 normal, Material m) {
  Primitive p;
  p.kind = Primitive::Kind::Plane;
  p.name = name;
  p.center = point;
  p.normal = glm::normalize(normal);
  p.material = m;
  return p;
}

Primitive rectangle(const std::string& name, dvec3 center, dvec3 normal, double halfU, double halfV, Material m) {
  Primitive p = plane(name, center, normal, m);
  p.kind = Primitive::Kind::Rectangle;
  p.halfSize = dvec3(halfU, 0, halfV);
  return p;
}

Primitive disk(const std::string& name, dvec3 center, dvec3 normal, double radius, Material m) {
  Primitive p = plane(name, center, normal, m);
  p.kind = Primitive::Kind::Disk;
  p.radius = radius;
  return p;
}

Primitive sphere(const std::string& name, dvec3 center, double radius, Material m) {
  Primitive p;
  p.kind = Primitive::Kind::Sphere;
  p.name = name;
  p.center = center;
  p.radius = radius;
  p.material = m;
  return p;
}

Primitive box(const std::string& name, dvec3 center, dvec3 halfSize, double yawDegrees, Material m) {
  Primitive p;
  p.kind = Primitive::Kind::Box;
  p.name = name;
  p.center = center;
  p.halfSize = halfSize;
  p.yawRadians = yawDegrees * kPi / 180.0;
  p.material = m;
  return p;
}

std::vector<std::string> sceneNames() { return {"spheres_on_mirror", "mirror_wall", "half_sky"}; }

Scene makeScene(const std::string& name) {
  const auto mat = [](double r, double g, double b) { return Material{dvec3(r, g, b)}; };
  const dvec3 up(0, 1, 0);
  Scene s;
  s.name = name;
  if (name == "spheres_on_mirror" || name == "half_sky") {
    s.primitives = {
        rectangle("floor", dvec3(0.0), up, 8, 8, mat(0.45, 0.45, 0.5)),
        sphere("red", dvec3(0, 1, 0), 1.0, mat(0.9, 0.3, 0.25)),
        sphere("green", dvec3(-4.9, 0.7, 2.4), 0.7, mat(0.3, 0.85, 0.35)),
        sphere("blue", dvec3(2.4, 0.9, -1.0), 0.9, mat(0.3, 0.45, 0.95)),
        sphere("yellow", dvec3(0.9, 0.5, 3.7), 0.5, mat(0.95, 0.85, 0.3)),
        sphere("purple", dvec3(-1.2, 1.3, -3.5), 1.3, mat(0.8, 0.5, 0.9)),
        box("orange_box", dvec3(-3.4, 0.8, -1.4), dvec3(0.6, 0.8, 0.6), 25, mat(0.95, 0.6, 0.3)),
        box("cyan_box", dvec3(5.0, 0.6, 1.0), dvec3(0.6, 0.6, 0.8), -35, mat(0.35, 0.85, 0.85)),
    };
    s.view.eye = dvec3(0, 4.5, 8.5);
    s.view.target = dvec3(0, 0.6, 0);  // pitch atan(3.9 / 8.5) ~ 24.6 degrees down
    if (name == "half_sky") {  // the same objects seen from low, looking level: sky fills the top half
      s.view.eye = dvec3(0, 1.2, 9.5);
      s.view.target = dvec3(0, 1.2, 0);
    }
  } else if (name == "mirror_wall") {
    s.primitives = {
        rectangle("floor", dvec3(0.0), up, 9, 9, mat(0.45, 0.45, 0.5)),
        box("wall", dvec3(-4.6, 2.0, -1.0), dvec3(0.1, 2.0, 6.0), -20, mat(0.6, 0.62, 0.7)),
        box("box_a", dvec3(-2.4, 0.6, -1.8), dvec3(0.6, 0.6, 0.6), 30, mat(0.95, 0.6, 0.3)),
        box("box_b", dvec3(0.2, 0.9, -3.0), dvec3(0.5, 0.9, 0.5), -20, mat(0.35, 0.85, 0.85)),
        box("box_c", dvec3(1.8, 0.4, -0.6), dvec3(0.8, 0.4, 0.5), 10, mat(0.9, 0.3, 0.25)),
        box("box_d", dvec3(-1.6, 0.3, 1.2), dvec3(0.3, 0.3, 0.3), 45, mat(0.95, 0.85, 0.3)),
        sphere("green", dvec3(0.9, 0.6, 1.6), 0.6, mat(0.3, 0.85, 0.35)),
        sphere("blue", dvec3(-2.9, 1.0, 0.6), 0.55, mat(0.3, 0.45, 0.95)),
    };
    s.view.eye = dvec3(2.5, 3.6, 7.0);
    s.view.target = dvec3(-1.0, 0.8, -1.5);  // pitch atan(2.8 / 9.19) ~ 17 degrees down
  } else {
    throw std::invalid_argument("unknown analytic scene: " + name);
  }
  return s;
}

Camera makeCamera(const ViewParams& view, int width, int height) {
  Camera c;
  c.width = width;
  c.height = height;
  c.view = glm::lookAt(view.eye, view.target, view.up);
  c.projection =
      glm::perspective(view.fovYDegrees * kPi / 180.0, double(width) / height, view.nearPlane, view.farPlane);
  c.nearPlane = view.nearPlane;
  c.farPlane = view.farPlane;
  return c;
}

Ray primaryRay(const Camera& camera, double sx, double sy) {
  const glm::dmat4 inv = glm::inverse(camera.projection * camera.view);
  const double nx = 2.0 * sx / camera.width - 1.0, ny = 1.0 - 2.0 * sy / camera.height;
  // NDC z = -1 (near) and 0 (finite even for an infinite far plane).
  const dvec4 a = inv * dvec4(nx, ny, -1.0, 1.0), b = inv * dvec4(nx, ny, 0.0, 1.0);
  Ray r;
  r.origin = dvec3(a) / a.w;
  r.direction = glm::normalize(dvec3(b) / b.w - r.origin);
  return r;
}

Hit intersect(const Scene& scene, const Ray& ray, double tMin) {
  Hit best;
  best.t = kInf;
  for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
    const Primitive& p = scene.primitives[i];
    dvec3 localNormal(0.0);
    double t = kInf;
    switch (p.kind) {
      case Primitive::Kind::Sphere:
        t = sphereT(p, ray, tMin);
        break;
      case Primitive::Kind::Box:
        t = boxT(p, ray, tMin, localNormal);
        break;
      default:
        t = planarT(p, ray, tMin);
        break;
    }
    if (!(t < best.t)) continue;
    best.primitive = int(i);
    best.t = t;
    best.position = ray.origin + t * ray.direction;
    if (p.kind == Primitive::Kind::Sphere) {
      best.normal = (best.position - p.center) / p.radius;
    } else if (p.kind == Primitive::Kind::Box) {
      best.normal = rotateY(localNormal, p.yawRadians);
    } else {
      best.normal = glm::dot(p.normal, ray.direction) < 0 ? p.normal : -p.normal;
    }
  }
  if (best.primitive < 0) best.t = 0.0;
  return best;
}

dvec3 colorAt(const Scene& scene, const Hit& hit) {
  if (!hit) return scene.skyColor;
  const Material& m = scene.primitives[std::size_t(hit.primitive)].material;
  if (!m.textured) return m.base;
  const double k = 2.0 * kPi / m.period;
  // Two oblique directions so every surface orientation sees variation.
  const double s1 = k * glm::dot(hit.position, glm::normalize(dvec3(0.8, 0.45, 0.4)));
  const double s2 = k * glm::dot(hit.position, glm::normalize(dvec3(-0.35, 0.6, 0.72)));
  dvec3 c;
  for (int ch = 0; ch < 3; ++ch)
    c[ch] = m.base[ch] * (0.6 + 0.2 * std::sin(s1 + 2.1 * ch) + 0.2 * std::sin(s2 + 1.3 * ch + 0.5));
  return c;
}

double planarDepth(const Camera& camera, const dvec3& world) { return -(camera.view * dvec4(world, 1.0)).z; }

dvec3 projectToScreen(const Camera& camera, const dvec3& world) {
  const dvec4 clip = camera.projection * camera.view * dvec4(world, 1.0);
  const double depth = planarDepth(camera, world);
  if (!(clip.w > 0)) return {std::nan(""), std::nan(""), depth};
  return {(clip.x / clip.w + 1.0) * 0.5 * camera.width, (1.0 - clip.y / clip.w) * 0.5 * camera.height, depth};
}

AnalyticGBuffer renderGBuffer(const Scene& scene, const Camera& camera) {
  const int w = camera.width, h = camera.height;
  AnalyticGBuffer g;
  g.width = w;
  g.height = h;
  g.color = Image(w, h, 3);
  g.depth = Image(w, h, 1);
  g.normal = Image(w, h, 3);
  g.roughness = Image(w, h, 1);
  g.hits.resize(std::size_t(w) * h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const Hit hit = intersect(scene, primaryRay(camera, x + 0.5, y + 0.5));
      g.hits[std::size_t(y) * w + x] = hit;
      const dvec3 c = colorAt(scene, hit);
      for (int ch = 0; ch < 3; ++ch) {
        g.color.at(x, y, ch) = float(c[ch]);
        g.normal.at(x, y, ch) = hit ? float(hit.normal[ch]) : 0.0f;
      }
      g.depth.at(x, y, 0) = hit ? float(planarDepth(camera, hit.position)) : float(kSkyDepth);
      g.roughness.at(x, y, 0) = hit ? float(scene.primitives[std::size_t(hit.primitive)].material.roughness) : 0.0f;
    }
  }
  return g;
}

const char* className(ReflectionClass c) {
  switch (c) {
    case ReflectionClass::NoSurface:
      return "NoSurface";
    case ReflectionClass::Visible:
      return "Visible";
    case ReflectionClass::OffScreen:
      return "OffScreen";
    case ReflectionClass::Occluded:
      return "Occluded";
    case ReflectionClass::Sky:
      return "Sky";
  }
  return "?";
}

MirrorSample reflectAt(const Scene& scene, const Camera& camera, const Hit& surface, const dvec3& viewDir) {
  MirrorSample s;
  if (!surface) return s;
  const dvec3 n = surface.normal;
  s.reflected.origin = surface.position;
  s.reflected.direction = glm::normalize(viewDir - 2.0 * glm::dot(viewDir, n) * n);
  // Relative tMin skips the ray's own surface without moving its origin.
  s.hit = intersect(scene, s.reflected, 1e-9 * (1.0 + glm::length(surface.position)));
  s.color = colorAt(scene, s.hit);
  if (!s.hit) {
    s.cls = ReflectionClass::Sky;
    return s;
  }
  s.screen = projectToScreen(camera, s.hit.position);
  const bool onScreen = s.screen.x >= 0 && s.screen.x < camera.width && s.screen.y >= 0 && s.screen.y < camera.height &&
                        s.screen.z >= camera.nearPlane && s.screen.z <= camera.farPlane;
  if (!onScreen) {
    s.cls = ReflectionClass::OffScreen;
    return s;
  }
  // Seen by the camera iff the primary ray through its projection lands on the same point from
  // the same side (the side check matters only for two-sided planar primitives).
  const Hit seen = intersect(scene, primaryRay(camera, s.screen.x, s.screen.y));
  const bool same = seen && glm::length(seen.position - s.hit.position) <= 1e-7 * (1.0 + s.screen.z) &&
                    glm::dot(seen.normal, s.hit.normal) > 0;
  s.cls = same ? ReflectionClass::Visible : ReflectionClass::Occluded;
  if (!same) return s;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx == 0 && dy == 0) continue;
      const Hit n = intersect(scene, primaryRay(camera, s.screen.x + dx, s.screen.y + dy));
      s.nearEdge = s.nearEdge || n.primitive != s.hit.primitive;
      const dvec3 c = colorAt(scene, n);
      for (int ch = 0; ch < 3; ++ch) s.colorSpread = std::max(s.colorSpread, std::abs(c[ch] - s.color[ch]));
      if (n)
        s.distanceSpread =
            std::max(s.distanceSpread, std::abs(glm::length(n.position - s.reflected.origin) - s.hit.t) / s.hit.t);
    }
  return s;
}

std::size_t MirrorTruth::count(ReflectionClass c) const {
  return std::size_t(std::count_if(samples.begin(), samples.end(), [c](const MirrorSample& s) { return s.cls == c; }));
}

MirrorTruth exactMirrorReflection(const Scene& scene, const Camera& camera, const AnalyticGBuffer& gbuffer) {
  MirrorTruth t;
  t.width = gbuffer.width;
  t.height = gbuffer.height;
  t.samples.resize(gbuffer.hits.size());
  for (int y = 0; y < t.height; ++y) {
    for (int x = 0; x < t.width; ++x) {
      const Hit& h = gbuffer.hit(x, y);
      if (h)
        t.samples[std::size_t(y) * t.width + x] =
            reflectAt(scene, camera, h, primaryRay(camera, x + 0.5, y + 0.5).direction);
    }
  }
  return t;
}

}  // namespace ssrcl::scenes
