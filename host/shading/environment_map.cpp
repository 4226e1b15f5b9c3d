// Equirectangular environments: reading one from EXR and prefiltering it for GGX lobes
// (include/ssrcl/environment.hpp has the mapping and what each level holds).
//
// Each rough level is a filtered-importance-sampled GGX convolution (Colbert and Krivanek 2007;
// Karis 2013's split sum): per texel, a fixed Hammersley set of lobe directions, each read from a
// box-filtered mip of the map whose texels match the solid angle that sample stands for, so a
// small bright feature (a sun) spreads smoothly over the lobe instead of landing on a few samples.

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <algorithm>
#include <cmath>
#include <new>
#include <thread>

#include "io/exr_header_check.hpp"
#include "ssrcl/environment.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl {
namespace {

constexpr double kPi = 3.14159265358979323846;
// kernels/common.cl's SSRCL_MAX_RADIANCE: weighted sums downstream cannot overflow float.
constexpr float kMaxRadiance = 1e20f;
constexpr int kLevels = 9;               // roughness 0, 1/8, ..., 1
constexpr int kMaxWidth = 4096;          // level 0 is box-reduced to at most this (mirror reflections need no more)
// Rough level k is level 0's width >> k, at most 1024 >> k (512 for roughness 1/8: texels of
// about a third of its lobe's width; finer costs seconds per map for nothing visible) and at least 32.
constexpr int kRoughWidthLimit = 1024, kMinRoughWidth = 32;
// Lobe samples per texel of a rough level: narrow lobes read fine mips, where few samples do.
int lobeSamples(int level) { return level <= 2 ? 64 : 256; }
constexpr long long kMaxInputPixels = 16384LL * 8192;  // a 16K map, 1.5 GiB as float RGB

struct Vec3 {
  double x, y, z;
};
Vec3 operator*(double s, Vec3 v) { return {s * v.x, s * v.y, s * v.z}; }
Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Vec3 normalize(Vec3 v) { return (1.0 / std::sqrt(dot(v, v))) * v; }

// Direction of continuous image position (u, v) in [0, 1]^2 (environment.hpp's mapping).
Vec3 directionAt(double u, double v) {
  const double phi = kPi * (1.0 - 2.0 * u), elevation = kPi * (0.5 - v);
  return {std::cos(elevation) * std::cos(phi), std::cos(elevation) * std::sin(phi), std::sin(elevation)};
}

// A bilinear read's row part at image height v in [0, 1] (clamped at the poles), which a lobe
// sample keeps along an image row.
struct MipRow {
  const Image* img;
  int y0, y1;
  double fy;
};
MipRow mipRow(const Image& img, double v) {
  const double y = std::clamp(v * img.height - 0.5, 0.0, img.height - 1.0);
  const int y0 = int(std::floor(y));
  return {&img, y0, std::min(y0 + 1, img.height - 1), y - std::floor(y)};
}

// The bilinear read at u in [-0.5, 1.5] on that row (a lobe sample shifted by at most half a
// turn), wrapping around in azimuth.
void sampleBilinear(const MipRow& row, double u, double out[3]) {
  const Image& img = *row.img;
  const double x = u * img.width - 0.5, fx = x - std::floor(x);
  int x0 = int(std::floor(x));
  x0 += x0 < 0 ? img.width : x0 >= img.width ? -img.width : 0;
  const int x1 = x0 + 1 == img.width ? 0 : x0 + 1;
  const float* a = img.data.data() + std::size_t(row.y0) * img.width * 3;
  const float* b = img.data.data() + std::size_t(row.y1) * img.width * 3;
  for (int c = 0; c < 3; ++c)
    out[c] = (1 - row.fy) * ((1 - fx) * a[3 * x0 + c] + fx * a[3 * x1 + c]) +
             row.fy * ((1 - fx) * b[3 * x0 + c] + fx * b[3 * x1 + c]);
}

// Half the size (rounded up), each texel the solid-angle-weighted mean of the up to 2x2 texels it
// covers (a row's texels shrink with the cosine of its latitude).
Image halve(const Image& img) {
  Image out(std::max(1, (img.width + 1) / 2), std::max(1, (img.height + 1) / 2), 3);
  auto rowWeight = [&](int y) { return std::cos(kPi * (0.5 - (y + 0.5) / img.height)); };
  for (int y = 0; y < out.height; ++y) {
    const int ya = std::min(2 * y, img.height - 1), yb = std::min(2 * y + 1, img.height - 1);
    const double wa = rowWeight(ya), wb = ya == yb ? 0.0 : rowWeight(yb);
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const int xa = std::min(2 * x, img.width - 1), xb = std::min(2 * x + 1, img.width - 1);
        out.at(x, y, c) = float((wa * (img.at(xa, ya, c) + img.at(xb, ya, c)) +
                                 wb * (img.at(xa, yb, c) + img.at(xb, yb, c))) / (2 * (wa + wb)));
      }
  }
  return out;
}

double radicalInverse(unsigned bits) {
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return bits * 2.3283064365386963e-10;
}

// One rough level: every texel's GGX lobe (n = v = its direction) read from the mip chain.
Image convolveLevel(const std::vector<Image>& mips, int width, double alpha, int samples) {
  Image out(width, std::max(1, width / 2), 3);
  // The sample set is the same around every texel: half-vectors in the tangent frame (z along n),
  // n.l, and half the log2 of the solid angle each stands for, 1 / (samples pdf(l)).
  struct LobeSample {
    double x, y, z, nl, halfLog2Angle;
  };
  std::vector<LobeSample> lobe;
  const double a2 = alpha * alpha;
  for (int s = 0; s < samples; ++s) {
    const double xi1 = (s + 0.5) / samples, phi = 2 * kPi * radicalInverse(unsigned(s));
    const double cosH = std::sqrt((1 - xi1) / (1 + (a2 - 1) * xi1)), sinH = std::sqrt(1 - cosH * cosH);
    const double nl = 2 * cosH * cosH - 1;
    if (nl <= 0) continue;
    const double denom = cosH * cosH * (a2 - 1) + 1;
    const double pdf = a2 / (kPi * denom * denom) / 4;  // D(h) (n.h) / (4 v.h), n = v
    lobe.push_back({sinH * std::cos(phi), sinH * std::sin(phi), cosH, nl, 0.5 * std::log2(1.0 / (samples * pdf))});
  }
  // Solid angle of a level-0 texel at the equator; it shrinks with cos(latitude) toward the poles.
  const double texelAngle = (2 * kPi / mips[0].width) * (kPi / mips[0].height);
  // Where a lobe sample of direction l reads: u, the rows of the two mips its solid angle picks
  // and their mix.
  struct LobeRead {
    double u, frac, nl;
    MipRow fine, coarse;
  };
  auto lobeRead = [&](Vec3 l, const LobeSample& s) {
    const double horizontal = std::hypot(l.x, l.y), v = 0.5 - std::atan2(l.z, horizontal) / kPi;
    const double lod = std::clamp(s.halfLog2Angle - 0.5 * std::log2(texelAngle * std::max(horizontal, 1e-3)), 0.0,
                                  mips.size() - 1.0);
    const int m0 = int(lod), m1 = std::min<int>(m0 + 1, int(mips.size()) - 1);
    return LobeRead{0.5 - std::atan2(l.y, l.x) / (2 * kPi), lod - m0, s.nl, mipRow(mips[m0], v), mipRow(mips[m1], v)};
  };
  // The lobe of the texel at u = 0.5 (azimuth 0) in row v, or where `u` is given, of that texel.
  auto lobeReads = [&](double u, double v, std::vector<LobeRead>& reads) {
    const Vec3 n = directionAt(u, v);
    const Vec3 t = normalize(cross(std::abs(n.z) < 0.999 ? Vec3{0, 0, 1} : Vec3{1, 0, 0}, n));
    const Vec3 b = cross(n, t);
    reads.clear();
    for (const LobeSample& s : lobe) {
      const Vec3 h = s.x * t + (s.y * b + s.z * n);
      reads.push_back(lobeRead((2 * s.z) * h + (-1.0) * n, s));
    }
  };
  auto rows = [&](int first, int step) {
    std::vector<LobeRead> reads;
    for (int y = first; y < out.height; y += step) {
      const double v = (y + 0.5) / out.height;
      // Off the poles a texel's frame is the row's first frame turned about the polar axis by the
      // texel's azimuth, and so are its lobe's directions: one set of angles, mips and rows serves
      // the image row, shifted in u (the arc tangents per texel were most of the prefilter's time).
      const bool turned = std::abs(directionAt(0.5, v).z) < 0.999;
      if (turned) lobeReads(0.5, v, reads);
      for (int x = 0; x < out.width; ++x) {
        const double u = (x + 0.5) / out.width;
        if (!turned) lobeReads(u, v, reads);
        const double shift = turned ? u - 0.5 : 0.0;
        double sum[3] = {0, 0, 0}, weight = 0;
        for (const LobeRead& r : reads) {
          double c0[3], c1[3];
          sampleBilinear(r.fine, r.u + shift, c0);
          sampleBilinear(r.coarse, r.u + shift, c1);
          for (int c = 0; c < 3; ++c) sum[c] += r.nl * (c0[c] + r.frac * (c1[c] - c0[c]));
          weight += r.nl;
        }
        for (int c = 0; c < 3; ++c) out.at(x, y, c) = float(sum[c] / weight);
      }
    }
  };
  const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(rows, i, threads);
  rows(0, threads);
  for (std::thread& t : pool) t.join();
  return out;
}

}  // namespace

EnvironmentMap prefilterEnvironment(const Image& equirect, const std::string& source) {
  const std::string name = source.empty() ? "environment" : source;
  if (equirect.channels < 3)
    throw Error(ErrorCode::InvalidInput, name + ": an environment needs RGB, the image has " +
                                             std::to_string(equirect.channels) + " channel(s)");
  if (equirect.width < 2 || equirect.width != 2 * equirect.height)
    throw Error(ErrorCode::InvalidInput, name + ": " + std::to_string(equirect.width) + "x" +
                                             std::to_string(equirect.height) +
                                             " is not an equirectangular (2:1 latitude-longitude) image");
  Image base(equirect.width, equirect.height, 3);
  for (size_t i = 0; i < size_t(base.width) * base.height; ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = equirect.data[i * equirect.channels + c];
      base.data[i * 3 + c] = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, kMaxRadiance);
    }
  while (base.width > kMaxWidth) base = halve(base);

  std::vector<Image> mips{base};
  while (mips.back().width > 4) mips.push_back(halve(mips.back()));
  EnvironmentMap env;
  env.source = source;
  env.levels.push_back(std::move(base));
  for (int k = 1; k < kLevels; ++k) {
    const int width =
        std::min(env.levels[0].width, std::max(kMinRoughWidth, std::min(env.levels[0].width, kRoughWidthLimit) >> k));
    const double roughness = double(k) / (kLevels - 1);
    env.levels.push_back(convolveLevel(mips, width, roughness * roughness, lobeSamples(k)));
  }
  return env;
}

EnvironmentMap loadEnvironmentMap(const std::string& path) {
  Image image;
  try {
    checkHeaderSizes(path);
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i window = header.dataWindow();
    const long long width = (long long)window.max.x - window.min.x + 1, height = (long long)window.max.y - window.min.y + 1;
    std::string missing;
    for (const char* c : {"R", "G", "B"})
      if (!header.channels().findChannel(c)) missing += missing.empty() ? c : std::string(", ") + c;
    if (!missing.empty()) {
      std::string present;
      for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
        present += (present.empty() ? "" : ", ") + std::string(it.name());
      throw Error(ErrorCode::InvalidInput, path + ": an environment needs channels R, G, B; missing " + missing +
                                               " (it has: " + (present.empty() ? "no channels" : present) + ")");
    }
    if (width <= 0 || height <= 0 || width * height > kMaxInputPixels)
      throw Error(ErrorCode::InvalidInput, path + ": " + std::to_string(width) + "x" + std::to_string(height) +
                                               " is empty or larger than an environment may be (16384x8192)");
    image = Image(int(width), int(height), 3);
    Imf::FrameBuffer frame;
    const size_t xStride = 3 * sizeof(float), yStride = xStride * size_t(width);
    char* origin = reinterpret_cast<char*>(image.data.data()) -
                   (ptrdiff_t(window.min.x) * ptrdiff_t(xStride) + ptrdiff_t(window.min.y) * ptrdiff_t(yStride));
    const char* names[] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, origin + c * sizeof(float), xStride, yStride));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw Error(ErrorCode::OutOfMemory, path + ": out of memory reading the environment");
  } catch (const std::exception& e) {  // OpenEXR's Iex exceptions
    throw Error(ErrorCode::IoError, path + ": cannot read the environment (" + e.what() + ")");
  }
  return prefilterEnvironment(image, path);
}

}  // namespace ssrcl
