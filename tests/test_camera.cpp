// Camera maths against GLM-built matrices, and the camera JSON sidecar.

#include <gtest/gtest.h>

#include <cmath>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/glm.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ssrcl/camera.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/io.hpp"
#include "support/exr_fixtures.hpp"
#include "support/temp_dir.hpp"

namespace ssrcl {
namespace {

using nlohmann::json;
constexpr double kPi = 3.14159265358979323846;

Camera lookAtCamera() {
  Camera camera;
  camera.width = 640;
  camera.height = 480;
  camera.nearPlane = 0.1;
  camera.farPlane = 100.0;
  camera.view = glm::lookAtRH(glm::dvec3(1, 2, 3), glm::dvec3(4, 2, -1), glm::dvec3(0, 1, 0));
  camera.projection = glm::perspectiveRH_NO(kPi / 3, 640.0 / 480.0, camera.nearPlane, camera.farPlane);
  return camera;
}

// Expects Error(code) whose message starts with `file` and contains each of `parts`, on one line.
template <class F>
void expectError(F&& action, ErrorCode code, const std::string& file, const std::vector<std::string>& parts) {
  try {
    action();
    ADD_FAILURE() << "no error thrown";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.code(), code) << message;
    EXPECT_EQ(message.rfind(file + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

struct Planes {
  double nearPlane, farPlane;
};
const Planes kPlanes[] = {{0.1, 100.0}, {1e-4, 1.0}, {1e-4, 1e3}, {0.01, 1e5}, {1.0, 1e7}, {2.5, 3.0}};

TEST(DeriveClipPlanes, Perspective) {
  for (const Planes& p : kPlanes) {
    for (const glm::dmat4& projection : {glm::perspectiveRH_NO(kPi / 3, 16.0 / 9.0, p.nearPlane, p.farPlane),
                                         glm::perspectiveRH_NO(0.2, 0.5, p.nearPlane, p.farPlane),
                                         glm::frustumRH_NO(-0.3 * p.nearPlane, 0.1 * p.nearPlane, -0.05 * p.nearPlane,
                                                           0.2 * p.nearPlane, p.nearPlane, p.farPlane)}) {
      double n = 0, f = 0;
      deriveClipPlanes(projection, n, f);
      EXPECT_NEAR(n, p.nearPlane, 1e-9 * p.nearPlane);
      // The far plane comes out of 1 + P22, which loses digits as far/near grows.
      EXPECT_NEAR(f, p.farPlane, 1e-6 * p.farPlane);
    }
  }
}

TEST(DeriveClipPlanes, InfinitePerspective) {
  for (double nearPlane : {1e-4, 0.1, 7.0}) {
    double n = 0, f = 0;
    deriveClipPlanes(glm::infinitePerspectiveRH(kPi / 4, 1.5, nearPlane), n, f);
    EXPECT_NEAR(n, nearPlane, 1e-12 * nearPlane);
    EXPECT_EQ(f, std::numeric_limits<double>::infinity());
  }
}

TEST(DeriveClipPlanes, Orthographic) {
  for (const Planes& p : kPlanes) {
    double n = 0, f = 0;
    deriveClipPlanes(glm::orthoRH_NO(-4.0, 6.0, -2.0, 3.0, p.nearPlane, p.farPlane), n, f);
    // Orthographic depth is linear, so both planes only lose precision relative to far.
    EXPECT_NEAR(n, p.nearPlane, 1e-12 * p.farPlane);
    EXPECT_NEAR(f, p.farPlane, 1e-12 * p.farPlane);
  }
}

TEST(DeriveClipPlanes, RejectsOtherConventions) {
  double n = 0, f = 0;
  // Left-handed: the last row is (0, 0, +1, 0).
  EXPECT_THROW(deriveClipPlanes(glm::perspectiveLH_NO(1.0, 1.0, 0.1, 10.0), n, f), Error);
  glm::dmat4 odd(1.0);
  odd[2][3] = 0.5;
  EXPECT_THROW(deriveClipPlanes(odd, n, f), Error);
  glm::dmat4 flat = glm::orthoRH_NO(-1.0, 1.0, -1.0, 1.0, 0.1, 10.0);
  flat[2][2] = 0.0;
  try {
    deriveClipPlanes(flat, n, f);
    FAIL() << "no error thrown";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidInput);
  }
}

TEST(CameraToScreen, LookAtCentreAndCorners) {
  const Camera camera = lookAtCamera();
  // The look-at target is 5 units straight ahead: centre of the screen.
  const glm::dvec3 target = glm::dvec3(camera.view * glm::dvec4(4, 2, -1, 1));
  const glm::dvec3 centre = cameraToScreen(camera, target);
  EXPECT_NEAR(centre.x, 320.0, 1e-9);
  EXPECT_NEAR(centre.y, 240.0, 1e-9);
  EXPECT_NEAR(centre.z, 5.0, 1e-12);

  // Points on the frustum's corner rays land on the image corners; +Y camera is the top row.
  const double depth = 7.0;
  const double halfHeight = depth * std::tan(kPi / 6);
  const double halfWidth = halfHeight * 640.0 / 480.0;
  const struct {
    glm::dvec3 point;
    double x, y;
  } corners[] = {{{-halfWidth, halfHeight, -depth}, 0, 0},
                 {{halfWidth, halfHeight, -depth}, 640, 0},
                 {{-halfWidth, -halfHeight, -depth}, 0, 480},
                 {{halfWidth, -halfHeight, -depth}, 640, 480}};
  for (const auto& corner : corners) {
    const glm::dvec3 s = cameraToScreen(camera, corner.point);
    EXPECT_NEAR(s.x, corner.x, 1e-9);
    EXPECT_NEAR(s.y, corner.y, 1e-9);
    EXPECT_NEAR(s.z, depth, 1e-12);
  }
}

TEST(CameraToScreen, Orthographic) {
  Camera camera = lookAtCamera();
  camera.projection = glm::orthoRH_NO(-4.0, 4.0, -3.0, 3.0, 0.1, 100.0);
  const glm::dvec3 s = cameraToScreen(camera, {4.0, 3.0, -50.0});
  EXPECT_NEAR(s.x, 640.0, 1e-9);
  EXPECT_NEAR(s.y, 0.0, 1e-9);
  EXPECT_EQ(s.z, 50.0);
  const glm::dvec3 q = cameraToScreen(camera, {-2.0, 0.0, -1.0});
  EXPECT_NEAR(q.x, 160.0, 1e-9);
  EXPECT_NEAR(q.y, 240.0, 1e-9);
}

TEST(ValidateCamera, AcceptsUsableCameras) {
  Camera camera = lookAtCamera();
  EXPECT_NO_THROW(validateCamera(camera, "cam.json"));
  // Millimetre scenes and extreme clip ranges are not "singular".
  camera.view = glm::scale(camera.view, glm::dvec3(1e-3));
  camera.projection = glm::perspectiveRH_NO(0.5, 1.0, 1e-4, 1e7);
  camera.nearPlane = 1e-4;
  camera.farPlane = 1e7;
  EXPECT_NO_THROW(validateCamera(camera, "cam.json"));
  // Georeferenced scenes put the camera far from the origin.
  camera.view = glm::lookAtRH(glm::dvec3(4e5, 1e3, -6e6), glm::dvec3(4e5 + 1, 1e3, -6e6), glm::dvec3(0, 1, 0));
  EXPECT_NO_THROW(validateCamera(camera, "cam.json"));
  camera.projection = glm::infinitePerspectiveRH(0.5, 1.0, 1e-4);
  camera.farPlane = std::numeric_limits<double>::infinity();
  EXPECT_NO_THROW(validateCamera(camera, "cam.json"));
}

TEST(ValidateCamera, RejectsUnusableCameras) {
  struct Case {
    const char* why;
    void (*change)(Camera&);
    const char* expected;
  };
  const Case cases[] = {
      {"zero view", [](Camera& c) { c.view = glm::dmat4(0.0); }, "view matrix is singular"},
      {"rank 3 view", [](Camera& c) { c.view[2] = c.view[0]; }, "view matrix is singular"},
      {"zero projection row", [](Camera& c) { c.projection[0][0] = 0.0; }, "projection matrix is singular"},
      {"rank 3 projection", [](Camera& c) { c.projection[3] = 2.0 * c.projection[2]; },
       "projection matrix is singular"},
      {"NaN in view", [](Camera& c) { c.view[1][2] = std::numeric_limits<double>::quiet_NaN(); }, "view"},
      {"inf in projection", [](Camera& c) { c.projection[0][0] = std::numeric_limits<double>::infinity(); },
       "projection"},
      {"zero width", [](Camera& c) { c.width = 0; }, "width"},
      {"negative height", [](Camera& c) { c.height = -480; }, "height"},
      {"near >= far", [](Camera& c) { c.nearPlane = c.farPlane; }, "near"},
      {"zero near", [](Camera& c) { c.nearPlane = 0.0; }, "near"},
      {"NaN near", [](Camera& c) { c.nearPlane = std::numeric_limits<double>::quiet_NaN(); }, "near"},
      {"NaN far", [](Camera& c) { c.farPlane = std::numeric_limits<double>::quiet_NaN(); }, "far"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.why);
    Camera camera = lookAtCamera();
    c.change(camera);
    expectError([&] { validateCamera(camera, "cam.json"); }, ErrorCode::InvalidInput, "cam.json", {c.expected});
  }
}

// Row-major JSON text of a matrix, as a renderer's exporter would write it.
json rows(const glm::dmat4& m) {
  json out = json::array();
  for (int r = 0; r < 4; ++r) out.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
  return out;
}

json validJson() {
  const Camera camera = lookAtCamera();
  return {{"view", rows(camera.view)}, {"projection", rows(camera.projection)}, {"width", 640}, {"height", 480}};
}

TEST(CameraJson, SaveLoadRoundTripsExactly) {
  test::TempDir dir;
  Camera camera = lookAtCamera();
  camera.view = glm::rotate(camera.view, 0.123456789, glm::dvec3(0.3, 0.4, 0.5));
  camera.nearPlane = 0.1 / 3.0;
  camera.projection = glm::perspectiveRH_NO(1.0 / 3.0, 4.0 / 3.0, camera.nearPlane, camera.farPlane);
  const std::string file = dir.file("cam.json");
  saveCameraJson(file, camera);
  const Camera loaded = loadCameraJson(file);
  EXPECT_EQ(loaded.view, camera.view);
  EXPECT_EQ(loaded.projection, camera.projection);
  EXPECT_EQ(loaded.width, camera.width);
  EXPECT_EQ(loaded.height, camera.height);
  EXPECT_EQ(loaded.nearPlane, camera.nearPlane);
  EXPECT_EQ(loaded.farPlane, camera.farPlane);
}

TEST(CameraJson, InfiniteFarRoundTrips) {
  test::TempDir dir;
  Camera camera = lookAtCamera();
  camera.projection = glm::infinitePerspectiveRH(1.0, 4.0 / 3.0, 0.1);
  camera.farPlane = std::numeric_limits<double>::infinity();
  saveCameraJson(dir.file("cam.json"), camera);
  EXPECT_TRUE(json::parse(test::readBytes(dir.file("cam.json")))["far"].is_null());
  EXPECT_EQ(loadCameraJson(dir.file("cam.json")).farPlane, camera.farPlane);
}

TEST(CameraJson, MatricesAreRowMajor) {
  test::TempDir dir;
  Camera camera = lookAtCamera();
  camera.view = glm::translate(glm::dmat4(1.0), glm::dvec3(1.5, -2.0, 3.25));
  saveCameraJson(dir.file("cam.json"), camera);
  const json written = json::parse(test::readBytes(dir.file("cam.json")));
  EXPECT_EQ(written["view"][0][3], 1.5);
  EXPECT_EQ(written["view"][2][3], 3.25);
  EXPECT_EQ(written["projection"][3][2], -1.0);

  json text = validJson();
  text["view"] = {{1, 0, 0, 10}, {0, 1, 0, 20}, {0, 0, 1, 30}, {0, 0, 0, 1}};
  test::writeBytes(dir.file("hand.json"), text.dump());
  const Camera loaded = loadCameraJson(dir.file("hand.json"));
  EXPECT_EQ(loaded.view[3][0], 10.0);
  EXPECT_EQ(loaded.view[3][2], 30.0);
}

TEST(CameraJson, DerivesMissingClipPlanes) {
  test::TempDir dir;
  json text = validJson();
  text["projection"] = rows(glm::perspectiveRH_NO(1.0, 1.0, 0.5, 200.0));
  test::writeBytes(dir.file("cam.json"), text.dump());
  Camera camera = loadCameraJson(dir.file("cam.json"));
  EXPECT_NEAR(camera.nearPlane, 0.5, 1e-12);
  EXPECT_NEAR(camera.farPlane, 200.0, 1e-9);

  text["near"] = 0.75;  // a given plane wins, the other is still derived
  test::writeBytes(dir.file("cam.json"), text.dump());
  camera = loadCameraJson(dir.file("cam.json"));
  EXPECT_EQ(camera.nearPlane, 0.75);
  EXPECT_NEAR(camera.farPlane, 200.0, 1e-9);

  // Both given: the projection need not be a recognised kind.
  text["projection"][3] = {0, 0, 1, 0};
  text["far"] = 10.0;
  test::writeBytes(dir.file("cam.json"), text.dump());
  EXPECT_EQ(loadCameraJson(dir.file("cam.json")).farPlane, 10.0);
}

TEST(CameraJson, BadContentNamesFileAndField) {
  struct Case {
    const char* why;
    std::string text;
    const char* expected;
  };
  const auto with = [](const char* field, json value) {
    json j = validJson();
    j[field] = std::move(value);
    return j.dump();
  };
  const auto without = [](const char* field) {
    json j = validJson();
    j.erase(field);
    return j.dump();
  };
  json textInRow = validJson();
  textInRow["view"][1][2] = "0.5";
  json shortRow = validJson();
  shortRow["projection"][2].erase(3);
  const Case cases[] = {
      {"missing view", without("view"), "missing field 'view'"},
      {"missing projection", without("projection"), "missing field 'projection'"},
      {"missing width", without("width"), "missing field 'width'"},
      {"missing height", without("height"), "missing field 'height'"},
      {"three rows", with("view", {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}),
       "field 'view' must be 4 rows of 4 numbers"},
      {"flat array", with("view", json::array({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1})), "field 'view'"},
      {"short row", shortRow.dump(), "field 'projection' must be 4 rows of 4 numbers"},
      {"text in a number", textInRow.dump(), "field 'view' must be 4 rows of 4 numbers"},
      {"view not an array", with("view", "identity"), "field 'view'"},
      {"width as text", with("width", "640"), "field 'width' must be a positive integer"},
      {"zero width", with("width", 0), "field 'width' must be a positive integer"},
      {"negative height", with("height", -2), "field 'height' must be a positive integer"},
      {"fractional width", with("width", 640.5), "field 'width'"},
      {"huge width", with("width", 1e12), "field 'width'"},
      {"near as text", with("near", "0.1"), "field 'near' must be a number"},
      {"near beyond far", with("far", 0.01), "near"},
      {"singular projection", with("projection", {{0, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, -1.1, -0.2}, {0, 0, -1, 0}}),
       "projection matrix is singular"},
      {"singular view", with("view", {{1, 0, 0, 0}, {1, 0, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}),
       "view matrix is singular"},
      {"unknown projection", with("projection", {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 1, 1}}),
       "field 'projection'"},
      {"invalid JSON", "{\n  \"width\": 640,\n  \"height\": \n}", "line 4"},
      {"empty file", "", "invalid JSON"},
      {"trailing garbage", validJson().dump() + " x", "invalid JSON"},
      {"not an object", "[1, 2, 3]", "JSON object"},
  };
  test::TempDir dir;
  const std::string file = dir.file("cam.json");
  for (const Case& c : cases) {
    SCOPED_TRACE(c.why);
    test::writeBytes(file, c.text);
    expectError([&] { loadCameraJson(file); }, ErrorCode::InvalidInput, file, {c.expected});
  }
}

TEST(CameraJson, FileErrorsAreIoErrors) {
  test::TempDir dir;
  const std::string missing = dir.file("missing.json");
  expectError([&] { loadCameraJson(missing); }, ErrorCode::IoError, missing, {"cannot open"});
  expectError([&] { loadCameraJson(dir.path().string()); }, ErrorCode::IoError, dir.path().string(), {"cannot read"});
  const std::string unwritable = dir.file("no/such/dir/cam.json");
  expectError([&] { saveCameraJson(unwritable, lookAtCamera()); }, ErrorCode::IoError, unwritable, {"cannot write"});
}

}  // namespace
}  // namespace ssrcl
