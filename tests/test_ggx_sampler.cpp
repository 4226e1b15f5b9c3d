// Statistical tests of the GGX visible-normal sampler (Heitz 2018) as kernels/ggx.cl implements it,
// the very source the tracer compiles, here compiled for the host (host/pipeline/opencl_c_on_host.hpp),
// against the double-precision textbook GGX in support/ggx_reference.hpp.
//
// Chi-square (the pbrt-v4 bsdfs_test approach): the sampled l are binned, each bin's expected count
// is N times the integral of the analytic l-density over it, bins expecting < 5 are pooled, and
// the p-value comes from the regularized incomplete gamma function. The sequence is low-discrepancy,
// so a correct sampler gives chi-square values far below the degrees of freedom; the test only
// asserts p above the Bonferroni-corrected threshold, and ChiSquareRejectsWrongHypotheses shows
// that the same procedure rejects a lobe that is slightly off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <functional>
#include <glm/geometric.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "support/ggx_probe.hpp"
#include "support/ggx_reference.hpp"

namespace {

using glm::dvec3;
namespace ggx = ssrcl::test::ggx;
using ggx::kPi;

// Unit view direction in the xz plane with N.V = cosTheta, as the float vector the kernel gets.
glm::vec3 viewWithCos(double cosTheta) {
  return glm::vec3(float(std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta))), 0.0f, float(cosTheta));
}

dvec3 toDouble(const glm::vec3& v) { return glm::normalize(dvec3(v)); }

// The direction of a kernel sample's float l, in double. Normalizing matters: the kernel's l is
// unit only to float rounding, which near the mirror direction at grazing views is a large error
// of o + l (and so of the half vector).
dvec3 sampleDirection(const glm::vec4& s) { return glm::normalize(dvec3(s.x, s.y, s.z)); }

double angle(const dvec3& a, const dvec3& b) { return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)); }

bool finiteDirection(const glm::vec4& s) { return std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.z); }
bool finite(const glm::vec4& s) { return finiteDirection(s) && std::isfinite(s.w); }

// ---- Chi-square distribution -------------------------------------------------------------------

// Regularized upper incomplete gamma Q(a, x): power series for x < a + 1, Lentz's continued
// fraction otherwise (Numerical Recipes 6.2). Accurate far into the tails, unlike Wilson-Hilferty.
double gammaQ(double a, double x) {
  if (!(x > 0)) return 1.0;
  const double prefix = std::exp(a * std::log(x) - x - std::lgamma(a));
  if (x < a + 1) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 100000 && term > sum * 1e-16; ++n) sum += term *= x / (a + n);
    return std::max(0.0, 1.0 - prefix * sum);
  }
  const double tiny = 1e-300;
  double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    c = b + an / c;
    d = 1 / (std::abs(d) < tiny ? tiny : d);
    c = std::abs(c) < tiny ? tiny : c;
    h *= d * c;
    if (std::abs(d * c - 1) < 1e-16) break;
  }
  return prefix * h;
}

double chiSquarePValue(double chi2, int dof) { return gammaQ(0.5 * dof, 0.5 * chi2); }

// ---- Binning -----------------------------------------------------------------------------------

// Bins over the l-sphere. Directions below the horizon (l.z <= 0: the pipeline gives them zero
// weight) are one bin. The others are binned by their half vector h = normalize(o + l), which
// has h.z > 0 there: by h's azimuth and v = 1 - cos of h's polar angle stretched to unit
// roughness, tan(stretched) = tan(theta_h) / alpha. In these the lobe spreads over the bins
// whatever alpha and the view (plain (cos theta, phi) bins of l would put a narrow lobe into one
// bin), and the l-density times the area element stays bounded, so midpoint quadrature converges.
// (Binning below-horizon l by h too would resolve the region around l = -o, where o + l turns the
// kernel's float rounding of l into large errors of h; nothing is traced there.)
class HalfVectorBins {
 public:
  static constexpr int kV = 16, kPhi = 32, kBelow = kV * kPhi, kCount = kBelow + 1;

  HalfVectorBins(const dvec3& o, double alpha) : o_(o), alpha_(alpha) {}

  int index(const dvec3& l) const {
    if (!(l.z > 0)) return kBelow;
    const dvec3 s = o_ + l;
    const double planar = std::sqrt(s.x * s.x + s.y * s.y);
    const double cosStretched = alpha_ * s.z / std::sqrt(alpha_ * alpha_ * s.z * s.z + planar * planar);
    const int iv = std::min(kV - 1, int((1.0 - cosStretched) * kV));
    const int ip = std::min(kPhi - 1, int((std::atan2(s.y, s.x) + kPi) / (2 * kPi) * kPhi));
    return iv * kPhi + ip;
  }

  // l of the half vector at v in [0, 1], phi in [-pi, pi].
  dvec3 direction(double v, double phi) const {
    const double cosStretched = 1.0 - v, sinStretched = std::sqrt(std::max(0.0, v * (2.0 - v)));
    const dvec3 h = glm::normalize(
        dvec3(alpha_ * sinStretched * std::cos(phi), alpha_ * sinStretched * std::sin(phi), cosStretched));
    return 2.0 * glm::dot(o_, h) * h - o_;
  }

  // Probability of every bin under `pdf` (solid-angle density of l) over the l reached from
  // h.z > 0 (all of the VNDF's l): midpoint rule on sub x sub cells per bin, refined where a cell
  // straddles the visibility edge o.h = 0 (a kink, finer than the bins at grazing views) or the
  // horizon l.z = 0.
  std::vector<double> probabilities(const std::function<double(const dvec3&)>& pdf, int sub = 4) const {
    std::vector<double> p(kCount, 0.0);
    const double dv = 1.0 / (kV * sub), dphi = 2 * kPi / (kPhi * sub);
    for (int iv = 0; iv < kV * sub; ++iv)
      for (int ip = 0; ip < kPhi * sub; ++ip)
        addCell(pdf, iv * dv, (iv + 1) * dv, -kPi + ip * dphi, -kPi + (ip + 1) * dphi, (iv / sub) * kPhi + ip / sub, 8,
                p);
    return p;
  }

 private:
  void addCell(const std::function<double(const dvec3&)>& pdf, double v0, double v1, double p0, double p1, int bin,
               int depth, std::vector<double>& p) const {
    const double vm = 0.5 * (v0 + v1), pm = 0.5 * (p0 + p1);
    if (depth > 0) {
      int zero = 0, below = 0;
      for (const dvec3& l :
           {direction(v0, p0), direction(v1, p0), direction(v0, p1), direction(v1, p1), direction(vm, pm)}) {
        zero += pdf(l) == 0;
        below += !(l.z > 0);
      }
      if ((zero > 0 && zero < 5) || (below > 0 && below < 5)) {
        addCell(pdf, v0, vm, p0, pm, bin, depth - 1, p);
        addCell(pdf, vm, v1, p0, pm, bin, depth - 1, p);
        addCell(pdf, v0, vm, pm, p1, bin, depth - 1, p);
        addCell(pdf, vm, v1, pm, p1, bin, depth - 1, p);
        return;
      }
    }
    // Area element |dl/dv x dl/dphi| by central differences.
    const double hv = 1e-3 * (v1 - v0), hp = 1e-3 * (p1 - p0);
    const dvec3 lv = direction(vm + hv, pm) - direction(vm - hv, pm);
    const dvec3 lp = direction(vm, pm + hp) - direction(vm, pm - hp);
    const dvec3 l = direction(vm, pm);
    p[l.z > 0 ? bin : kBelow] += pdf(l) * glm::length(glm::cross(lv, lp)) / (4 * hv * hp) * (v1 - v0) * (p1 - p0);
  }

  dvec3 o_;
  double alpha_;
};

struct ChiSquare {
  double chi2 = 0;
  int dof = 0;
  double pValue = 1;
  double covered = 0;  // the hypothesis' probability over the l reached from h.z > 0
};

// Tests `samples` against the l-density `pdf` of view o; alpha only sets the binning. The
// below-horizon bin expects all the probability the others do not (mass outside h.z > 0 too).
ChiSquare chiSquareTest(const std::vector<glm::vec4>& samples, const dvec3& o, double alpha,
                        const std::function<double(const dvec3&)>& pdf) {
  const HalfVectorBins bins(o, alpha);
  std::vector<double> observed(HalfVectorBins::kCount, 0.0);
  for (const glm::vec4& s : samples) observed[bins.index(sampleDirection(s))] += 1;
  std::vector<double> expected = bins.probabilities(pdf);
  ChiSquare r;
  for (double e : expected) r.covered += e;
  expected[HalfVectorBins::kBelow] += std::max(0.0, 1.0 - r.covered);
  for (double& e : expected) e *= double(samples.size());

  // Bins expecting fewer than 5 are pooled into one (into the smallest other bin if still < 5).
  std::vector<std::pair<double, double>> cells;  // (expected, observed)
  double poolE = 0, poolO = 0;
  for (int i = 0; i < HalfVectorBins::kCount; ++i) {
    if (expected[i] < 5) {
      poolE += expected[i];
      poolO += observed[i];
    } else {
      cells.emplace_back(expected[i], observed[i]);
    }
  }
  if (poolE >= 5 || cells.empty()) {
    cells.emplace_back(poolE, poolO);
  } else {
    auto smallest = std::min_element(cells.begin(), cells.end());
    smallest->first += poolE;
    smallest->second += poolO;
  }
  for (const auto& [e, n] : cells) r.chi2 += e > 0 ? (n - e) * (n - e) / e : (n > 0 ? INFINITY : 0.0);
  r.dof = int(cells.size()) - 1;
  r.pValue = chiSquarePValue(r.chi2, r.dof);
  return r;
}

// ---- The sampler's distribution and density --------------------------------------------------

ChiSquare vndfChiSquare(const std::vector<glm::vec4>& samples, const dvec3& o, double alpha) {
  return chiSquareTest(samples, o, alpha, [&](const dvec3& l) { return ggx::vndfReflectionPdf(o, l, alpha); });
}

struct LobeCase {
  std::string name;
  double alpha;
  double cosView;  // N.V
};

std::ostream& operator<<(std::ostream& out, const LobeCase& c) { return out << c.name; }

// Roughness 0.05, 0.5, 1 through the default mapping alpha = r^2, alpha 0.05, 0.5 directly (alpha 1
// is both) and alpha 1e-4, the floor trace.cl clamps to, at N.V = 1, 0.5, 0.1, 1e-3.
std::vector<LobeCase> lobeCases() {
  const std::pair<const char*, double> alphas[] = {{"r0p05sq", 0.05 * 0.05}, {"r0p5sq", 0.5 * 0.5},
                                                   {"alpha1", 1.0},          {"alpha0p05", 0.05},
                                                   {"alpha0p5", 0.5},        {"alpha1em4", 1e-4}};
  const std::pair<const char*, double> views[] = {{"NV1", 1.0}, {"NV0p5", 0.5}, {"NV0p1", 0.1}, {"NV1em3", 1e-3}};
  std::vector<LobeCase> cases;
  for (const auto& [an, a] : alphas)
    for (const auto& [vn, c] : views) cases.push_back({std::string(an) + "_" + vn, a, c});
  return cases;
}

constexpr int kSamples = 1 << 20;
// Family-wise significance 1e-3, Bonferroni-corrected over the chi-square cases.
const double kThreshold = 1e-3 / double(lobeCases().size());

class GgxLobe : public ::testing::TestWithParam<LobeCase> {};

TEST_P(GgxLobe, ChiSquareMatchesAnalyticDensity) {
  const LobeCase c = GetParam();
  const glm::vec3 of = viewWithCos(c.cosView);
  const dvec3 o = toDouble(of);
  const auto samples = ssrcl::test::sampleGgxDirections(of, float(c.alpha), kSamples, 17);
  ASSERT_TRUE(std::all_of(samples.begin(), samples.end(), finiteDirection));
  const ChiSquare r = vndfChiSquare(samples, o, c.alpha);
  // The reference integrates to 1 over the l of h.z > 0: a check of it and of the quadrature.
  EXPECT_NEAR(r.covered, 1.0, 1e-3);
  EXPECT_GT(r.pValue, kThreshold) << "chi2 " << r.chi2 << " dof " << r.dof;
  RecordProperty("chi2", std::to_string(r.chi2));
  RecordProperty("dof", std::to_string(r.dof));
  RecordProperty("p", std::to_string(r.pValue));
}

// The pdf the kernel reports against the reference at the same l. Float evaluation of
// normalize(o + l) has an error near FLT_EPSILON / |o + l| in h, which D turns into a relative
// error up to about 2 / alpha times that, so the bound widens where that dominates (small alpha
// at grazing views; measured: at most 1.8 times that term).
TEST_P(GgxLobe, KernelPdfMatchesReference) {
  const LobeCase c = GetParam();
  const glm::vec3 of = viewWithCos(c.cosView);
  const dvec3 o = toDouble(of);
  const auto samples = ssrcl::test::sampleGgxDirections(of, float(c.alpha), 1 << 16, 5);
  int wrong = 0;
  for (const glm::vec4& s : samples) {
    const dvec3 l = sampleDirection(s);
    const double ref = ggx::vndfReflectionPdf(o, l, c.alpha);
    const double tol = 1e-3 + 8 * FLT_EPSILON / (c.alpha * glm::length(o + l));
    const bool ok = ref > 0 ? std::abs(s.w - ref) <= tol * ref : s.w == 0;
    if (!ok && ++wrong <= 5)
      ADD_FAILURE() << "l (" << l.x << ", " << l.y << ", " << l.z << "): kernel pdf " << s.w << ", reference " << ref;
  }
  EXPECT_EQ(wrong, 0);
}

INSTANTIATE_TEST_SUITE_P(Cases, GgxLobe, ::testing::ValuesIn(lobeCases()),
                         [](const ::testing::TestParamInfo<LobeCase>& info) { return info.param.name; });

// The same procedure must reject samples that are close to, but not, the hypothesis: alpha 10%
// off, and the common mistake of sampling the NDF D(h) cos(theta_h) instead of the visible normals.
TEST(GgxSampler, ChiSquareRejectsWrongHypotheses) {
  for (const auto& lobe : {std::pair{0.25, 0.5}, std::pair{0.0025, 0.1}}) {
    const double alpha = lobe.first, cosView = lobe.second;  // named, not bound: lambdas capture them
    const glm::vec3 of = viewWithCos(cosView);
    const dvec3 o = toDouble(of);
    const auto samples = ssrcl::test::sampleGgxDirections(of, float(alpha), kSamples, 17);
    const ChiSquare offAlpha = vndfChiSquare(samples, o, 1.1 * alpha);
    EXPECT_LT(offAlpha.pValue, kThreshold)
        << "alpha " << alpha << ": chi2 " << offAlpha.chi2 << " dof " << offAlpha.dof;
    const ChiSquare ndf = chiSquareTest(samples, o, alpha, [&](const dvec3& l) {
      const dvec3 h = glm::normalize(o + l);
      return ggx::ndf(h, alpha) * h.z / (4 * glm::dot(o, h));
    });
    EXPECT_LT(ndf.pValue, kThreshold) << "alpha " << alpha << ": chi2 " << ndf.chi2 << " dof " << ndf.dof;
    RecordProperty("alpha" + std::to_string(alpha) + "_chi2_alpha_x1.1", std::to_string(offAlpha.chi2));
    RecordProperty("alpha" + std::to_string(alpha) + "_chi2_ndf", std::to_string(ndf.chi2));
  }
}

// Values from chi-square tables (and Q(1, x) = exp(-x) for 2 degrees of freedom).
TEST(GgxSampler, ChiSquarePValueMatchesTables) {
  EXPECT_NEAR(chiSquarePValue(3.0, 2), std::exp(-1.5), 1e-12);
  EXPECT_NEAR(chiSquarePValue(18.307, 10), 0.05, 1e-4);
  EXPECT_NEAR(chiSquarePValue(124.342, 100), 0.05, 1e-4);
  EXPECT_NEAR(chiSquarePValue(359.906, 300), 0.01, 1e-4);
  EXPECT_NEAR(chiSquarePValue(1.0, 1), 0.317311, 1e-6);
  EXPECT_LT(chiSquarePValue(2000, 500), 1e-100);
}

// The reference itself integrates to 1 over the whole sphere, in polar coordinates (psi, beta) of l
// around the mirror direction with psi = pi t^2 to resolve narrow lobes: a parameterization
// independent of the half-vector bins.
TEST(GgxSampler, ReferencePdfIntegratesToOne) {
  const int nT = 1500, nBeta = 800;
  for (double alpha : {0.0025, 0.05, 0.25, 0.5, 1.0})
    for (double cosView : {1.0, 0.5, 0.1}) {
      const dvec3 o = toDouble(viewWithCos(cosView)), m = ggx::mirror(o);
      const dvec3 e1 = glm::normalize(dvec3(-m.z, 0, m.x)), e2 = glm::cross(m, e1);
      double sum = 0;
      for (int i = 0; i < nT; ++i) {
        const double t = (i + 0.5) / nT, psi = kPi * t * t, dpsi = 2 * kPi * t / nT;
        for (int j = 0; j < nBeta; ++j) {
          const double beta = 2 * kPi * (j + 0.5) / nBeta;
          const dvec3 l = std::cos(psi) * m + std::sin(psi) * (std::cos(beta) * e1 + std::sin(beta) * e2);
          sum += ggx::vndfReflectionPdf(o, l, alpha) * std::sin(psi) * dpsi;
        }
      }
      EXPECT_NEAR(sum * 2 * kPi / nBeta, 1.0, 1e-3) << "alpha " << alpha << " N.V " << cosView;
    }
}

// alpha 1e-8 (roughness 1e-4), down to N.V = 1e-6 and for a tiny unnormalized o: everything finite,
// a density for every l, all but 1e-4 of the samples within 1e-5 rad (1000 alpha) of the mirror
// direction and none past 0.1 rad (no sample thrown to the horizon). Not all within 1e-3: GGX's
// tail is real at any alpha, and the 24-bit sequence's extreme u = 1 - 2^-24 lands 1.3e-3 rad away
// at N.V = 1e-6 (a double-precision sampler: 2.9e-3). alpha 1e-4 reaches ~0.1 rad in 1e6 samples
// and is tested by the chi-square cases instead.
TEST(GgxSampler, NearDeltaLobeStaysAtMirrorDirection) {
  const float alpha = 1e-8f;
  for (const glm::vec3& of :
       {viewWithCos(1.0), viewWithCos(0.5), viewWithCos(1e-3), viewWithCos(1e-6), glm::vec3(1e-3f, 0.0f, 1e-9f)}) {
    const dvec3 o = toDouble(of), mirror = ggx::mirror(o);
    const auto samples = ssrcl::test::sampleGgxDirections(of, alpha, 1 << 18, 3);
    int outside = 0;
    double worst = 0;
    for (const glm::vec4& s : samples) {
      ASSERT_TRUE(finite(s)) << "o.z " << o.z;
      ASSERT_GT(s.w, 0.0f) << "o.z " << o.z;
      const double a = angle(sampleDirection(s), mirror);
      outside += a > 1e-5;
      worst = std::max(worst, a);
    }
    EXPECT_LE(outside, int(samples.size()) / 10000) << "o.z " << o.z;
    EXPECT_LT(worst, 0.1) << "o.z " << o.z;
  }
}

bool isUnit(const glm::vec4& s) { return std::abs(glm::length(glm::vec3(s)) - 1.0f) < 1e-5f; }

TEST(GgxSampler, ExtremeInputsGiveFiniteOutputs) {
  const int n = 1 << 14;
  // alpha 0 exactly: the exact mirror direction. Its density is a delta; the kernel's pdf there
  // (0 / 0 in ggx_d) is left unchecked, as trace.cl clamps alpha to >= 1e-4.
  for (double cosView : {1.0, 0.5, 1e-3}) {
    const glm::vec3 of = viewWithCos(cosView);
    const dvec3 mirror = ggx::mirror(toDouble(of));
    for (const glm::vec4& s : ssrcl::test::sampleGgxDirections(of, 0.0f, n, 1)) {
      ASSERT_TRUE(finiteDirection(s));
      ASSERT_LT(angle(sampleDirection(s), mirror), 1e-6) << "N.V " << cosView;
    }
  }
  // alpha up to 1 at normal, oblique and grazing views, and N.V = 0 exactly for every alpha (no
  // density there: pdf 0).
  for (float alpha : {0.0f, 1e-4f, 0.25f, 1.0f})
    for (double cosView : {1.0, 0.5, 1e-3, 0.0}) {
      if (alpha == 0.0f && cosView > 0) continue;  // done above
      for (const glm::vec4& s : ssrcl::test::sampleGgxDirections(viewWithCos(cosView), alpha, n, 1)) {
        ASSERT_TRUE(finite(s) && isUnit(s) && s.w >= 0) << "alpha " << alpha << " N.V " << cosView;
        if (cosView == 0.0) ASSERT_EQ(s.w, 0.0f) << "alpha " << alpha;
      }
    }
  // o of any length: the hook normalizes it.
  const glm::vec3 unit = glm::normalize(glm::vec3(3, 4, 5));
  const auto ref = ssrcl::test::sampleGgxDirections(unit, 0.25f, n, 1);
  for (float scale : {1e-15f, 1e-3f, 1e3f, 1e15f}) {
    const auto scaled = ssrcl::test::sampleGgxDirections(unit * scale, 0.25f, n, 1);
    for (int i = 0; i < n; ++i) {
      ASSERT_LT(glm::length(glm::vec3(scaled[i]) - glm::vec3(ref[i])), 1e-5f) << "scale " << scale;
      ASSERT_NEAR(scaled[i].w, ref[i].w, 1e-4f * ref[i].w) << "scale " << scale;
    }
  }
}

TEST(GgxSampler, SameSeedSameBitsOtherSeedOtherSamples) {
  const glm::vec3 of = viewWithCos(0.5);
  const int n = 1 << 16;
  const auto a = ssrcl::test::sampleGgxDirections(of, 0.25f, n, 7);
  const auto b = ssrcl::test::sampleGgxDirections(of, 0.25f, n, 7);
  const auto c = ssrcl::test::sampleGgxDirections(of, 0.25f, n, 8);
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)), 0);
  int same = 0;
  for (int i = 0; i < n; ++i) same += glm::vec3(a[i]) == glm::vec3(c[i]);
  EXPECT_LT(same, n / 1000);
}

}  // namespace
