#include <cerrno>
#include <climits>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "ssrcl/error.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl {
namespace {

using nlohmann::json;

[[noreturn]] void fail(ErrorCode code, const std::string& path, const std::string& problem) {
  throw Error(code, path + ": " + problem);
}

const json& required(const json& root, const std::string& path, const char* field) {
  const auto it = root.find(field);
  if (it == root.end()) fail(ErrorCode::InvalidInput, path, std::string("missing field '") + field + "'");
  return *it;
}

// Matrices are stored row-major, as written on paper; GLM indexes m[column][row].
glm::dmat4 readMatrix(const json& root, const std::string& path, const char* field) {
  const json& rows = required(root, path, field);
  const auto bad = [&] {
    fail(ErrorCode::InvalidInput, path, std::string("field '") + field + "' must be 4 rows of 4 numbers");
  };
  if (!rows.is_array() || rows.size() != 4) bad();
  glm::dmat4 m(0.0);
  for (int r = 0; r < 4; ++r) {
    const json& row = rows[r];
    if (!row.is_array() || row.size() != 4) bad();
    for (int c = 0; c < 4; ++c) {
      if (!row[c].is_number()) bad();
      m[c][r] = row[c].get<double>();
    }
  }
  return m;
}

int readSize(const json& root, const std::string& path, const char* field) {
  const json& value = required(root, path, field);
  if (!value.is_number_integer() || value.get<long long>() <= 0 || value.get<long long>() > INT_MAX)
    fail(ErrorCode::InvalidInput, path, std::string("field '") + field + "' must be a positive integer");
  return int(value.get<long long>());
}

// Returns false when the field is absent. "far": null stands for an infinite far plane, which
// JSON numbers cannot express.
bool readPlane(const json& root, const std::string& path, const char* field, double& value) {
  const auto it = root.find(field);
  if (it == root.end()) return false;
  if (it->is_null() && std::strcmp(field, "far") == 0) {
    value = INFINITY;
    return true;
  }
  if (!it->is_number()) fail(ErrorCode::InvalidInput, path, std::string("field '") + field + "' must be a number");
  value = it->get<double>();
  return true;
}

json matrixToJson(const glm::dmat4& m) {
  json rows = json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
  return rows;
}

}  // namespace

Camera loadCameraJson(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(ErrorCode::IoError, path, std::string("cannot open (") + std::strerror(errno) + ")");
  json root;
  try {
    root = json::parse(in);
  } catch (const json::parse_error& e) {
    // what() is "[json.exception.parse_error.101] parse error at line L, column C: ..."
    const std::string what = e.what();
    const auto start = what.find("] ");
    fail(ErrorCode::InvalidInput, path,
         "invalid JSON: " + (start == std::string::npos ? what : what.substr(start + 2)));
  } catch (const json::exception& e) {  // e.g. out_of_range.406: a number beyond double (1e999)
    const std::string what = e.what();
    const auto start = what.find("] ");
    fail(ErrorCode::InvalidInput, path,
         "invalid JSON: " + (start == std::string::npos ? what : what.substr(start + 2)));
  } catch (const std::exception& e) {  // read errors, e.g. a directory, surface as ios_failure
    fail(ErrorCode::IoError, path, std::string("cannot read (") + e.what() + ")");
  }
  if (!root.is_object()) fail(ErrorCode::InvalidInput, path, "top level must be a JSON object");

  Camera camera;
  camera.view = readMatrix(root, path, "view");
  camera.projection = readMatrix(root, path, "projection");
  camera.width = readSize(root, path, "width");
  camera.height = readSize(root, path, "height");
  double nearPlane = 0.0, farPlane = 0.0;
  const bool hasNear = readPlane(root, path, "near", nearPlane);
  const bool hasFar = readPlane(root, path, "far", farPlane);
  if (!hasNear || !hasFar) {
    try {
      deriveClipPlanes(camera.projection, camera.nearPlane, camera.farPlane);
    } catch (const Error& e) {
      fail(ErrorCode::InvalidInput, path, std::string("field 'projection': ") + e.what() + "; give 'near' and 'far'");
    }
  }
  if (hasNear) camera.nearPlane = nearPlane;
  if (hasFar) camera.farPlane = farPlane;
  validateCamera(camera, path.c_str());
  return camera;
}

void saveCameraJson(const std::string& path, const Camera& camera) {
  const json root = {
      {"view", matrixToJson(camera.view)},
      {"projection", matrixToJson(camera.projection)},
      {"width", camera.width},
      {"height", camera.height},
      {"near", camera.nearPlane},
      {"far", std::isinf(camera.farPlane) ? json(nullptr) : json(camera.farPlane)},
  };
  std::ofstream out(path);
  // nlohmann writes doubles with enough digits to round-trip exactly.
  if (out) out << root.dump(2) << '\n';
  out.close();
  if (!out) fail(ErrorCode::IoError, path, std::string("cannot write (") + std::strerror(errno) + ")");
}

}  // namespace ssrcl
