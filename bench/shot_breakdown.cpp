#include "shot_breakdown.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>

#include "support/exr_fixtures.hpp"
#include "support/shot_metric.hpp"

namespace ssrcl::bench {
namespace {

// The band along the frame's edges: 8% of its width or height.
constexpr double kEdgeBand = 0.08;

struct Pool {
  double se = 0, seReference = 0, sePass = 0;
  size_t pixels = 0;
};

// The reference with its values zeroed: against it, a pass's own change along the surface.
test::CyclesReference blanked(test::CyclesReference r) {
  std::fill(r.cycles.begin(), r.cycles.end(), 0.0);
  return r;
}

// Per pixel of frame t from frame t-1 (NaN where left out), each squared error summed over the
// channels: the pass's temporal error, the references' own change (a pass of zeros) and the pass's
// own change (against prevBlank and blank, the references zeroed).
struct ErrorMaps {
  std::vector<double> se, seReference, sePass;
};
ErrorMaps errorMaps(const test::CyclesReference& prevRef, const Image& prevPass, const test::CyclesReference& ref,
                    const Image& pass, const test::CyclesReference& prevBlank, const test::CyclesReference& blank) {
  ErrorMaps m;
  test::temporalError(prevRef, prevPass, ref, pass, &m.se);
  const Image zeros(pass.width, pass.height, pass.channels);
  test::temporalError(prevRef, zeros, ref, zeros, &m.seReference);
  test::temporalError(prevBlank, prevPass, blank, pass, &m.sePass);
  return m;
}

}  // namespace

std::vector<std::vector<uint8_t>> classifyPixels(const std::vector<std::string>& mediumPasses) {
  std::vector<std::vector<uint8_t>> out;
  for (const std::string& path : mediumPasses) {
    const test::ExrContents exr = test::readExr(path);
    const auto it = exr.channels.find("distance");
    if (it == exr.channels.end()) throw std::runtime_error(path + ": no channel distance");
    const int w = exr.width, h = exr.height;
    std::vector<uint8_t> classes(size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        if (!(it->second.values[i] > 0.0f)) classes[i] |= kMiss;
        if (x < kEdgeBand * w) classes[i] |= kLeft;
        if (x >= (1 - kEdgeBand) * w) classes[i] |= kRight;
        if (y < kEdgeBand * h) classes[i] |= kTop;
        if (y >= (1 - kEdgeBand) * h) classes[i] |= kBottom;
        if (classes[i] & (kLeft | kRight | kTop | kBottom)) classes[i] |= kEdge;
      }
    out.push_back(std::move(classes));
  }
  return out;
}

void printBreakdown(std::ostream& out, const std::string& label, const std::vector<test::CyclesReference>& refs,
                    const std::vector<Image>& passes, const std::vector<std::vector<uint8_t>>& classes,
                    const std::vector<Image>* alone) {
  const char* names[] = {"all",        "environment", "hit",   "edge band", "interior", "unblended",
                         "unbl. env.", "left",        "right", "top",       "bottom"};
  constexpr int kClasses = 11;
  Pool pools[kClasses];
  double peak = 0;
  std::vector<test::CyclesReference> blank;
  for (const test::CyclesReference& r : refs) blank.push_back(blanked(r));
  for (size_t t = 1; t < refs.size(); ++t) {
    const auto [se, seReference, sePass] =
        errorMaps(refs[t - 1], passes[t - 1], refs[t], passes[t], blank[t - 1], blank[t]);
    peak += refs[t].peak / double(refs.size() - 1);
    for (size_t i = 0; i < se.size(); ++i) {
      if (std::isnan(se[i])) continue;
      const uint8_t c = classes[t][i];
      bool unblended = false;
      if (alone) {
        unblended = true;
        for (int ch = 0; ch < 3; ++ch)
          unblended = unblended && passes[t].data[size_t(passes[t].channels) * i + size_t(ch)] ==
                                       (*alone)[t].data[size_t((*alone)[t].channels) * i + size_t(ch)];
      }
      const bool in[kClasses] = {true,
                                 (c & kMiss) != 0,
                                 !(c & kMiss),
                                 (c & kEdge) != 0,
                                 !(c & kEdge),
                                 unblended,
                                 unblended && (c & kMiss),
                                 (c & kLeft) != 0,
                                 (c & kRight) != 0,
                                 (c & kTop) != 0,
                                 (c & kBottom) != 0};
      for (int k = 0; k < kClasses; ++k)
        if (in[k])
          pools[k].se += se[i], pools[k].seReference += seReference[i], pools[k].sePass += sePass[i], ++pools[k].pixels;
    }
  }
  const auto db = [&](double se, size_t n) {
    return n ? 20 * std::log10(peak / std::sqrt(se / (3.0 * double(n)))) : NAN;
  };
  out << label
      << ": class, share of pixels, share of TE^2, tPSNR there; the references' change there and the "
         "pass's, as tPSNR (dB)\n"
      << std::fixed << std::setprecision(2);
  for (int k = 0; k < kClasses; ++k) {
    if ((k == 5 || k == 6) && !alone) continue;  // "unblended" needs the frames alone
    const Pool& p = pools[k];
    out << "  " << std::left << std::setw(12) << names[k] << std::right << std::setw(8)
        << 100.0 * double(p.pixels) / double(pools[0].pixels) << "%" << std::setw(8) << 100.0 * p.se / pools[0].se
        << "%" << std::setw(8) << db(p.se, p.pixels) << std::setw(8) << db(p.seReference, p.pixels) << std::setw(8)
        << db(p.sePass, p.pixels) << "\n";
  }
}

void writeTemporalPanels(const std::string& path, const test::CyclesReference& prevRef, const Image& prevPass,
                         const test::CyclesReference& ref, const Image& pass) {
  const auto [se, seReference, sePass] = errorMaps(prevRef, prevPass, ref, pass, blanked(prevRef), blanked(ref));
  const int w = pass.width, h = pass.height;
  constexpr int kPanels = 5;
  std::vector<unsigned char> rgb(size_t(kPanels * w) * h * 3, 0);
  const auto put = [&](int panel, size_t i, int c, double v) {
    const double g = std::pow(std::clamp(v / ref.peak, 0.0, 1.0), 1 / 2.2);
    rgb[((i / size_t(w)) * kPanels * w + size_t(panel * w) + i % size_t(w)) * 3 + size_t(c)] =
        static_cast<unsigned char>(255 * g + 0.5);
  };
  for (size_t k = 0; k < ref.pixels.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      put(0, size_t(ref.pixels[k]), c, pass.data[size_t(pass.channels) * size_t(ref.pixels[k]) + size_t(c)]);
      put(1, size_t(ref.pixels[k]), c, ref.cycles[3 * k + size_t(c)]);
    }
  for (size_t i = 0; i < se.size(); ++i) {
    if (std::isnan(se[i])) continue;
    for (int c = 0; c < 3; ++c) {
      put(2, i, c, std::sqrt(se[i] / 3));
      put(3, i, c, std::sqrt(seReference[i] / 3));
      put(4, i, c, std::sqrt(sePass[i] / 3));
    }
  }
  std::ofstream f(path, std::ios::binary);
  f << "P6\n" << kPanels * w << " " << h << "\n255\n";
  f.write(reinterpret_cast<const char*>(rgb.data()), std::streamsize(rgb.size()));
  if (!f) throw std::runtime_error(path + ": cannot write");
}

}  // namespace ssrcl::bench
