// The trace's native roofline against ssrcl's OpenCL trace stage, alternated round by round in
// one process (docs/BENCHMARKS.md, native roofline): the mirror rays of every reflecting pixel, then a glossy frame
// (samples GGX VNDF rays a pixel), both by the min-max packet trace of bench/packet_hiz_trace,
// with its steps per ray, lane use and cost per step, and the experiments on what bounds it.
//   ssrcl_trace_roofline [width height rounds scene roughness samples [native|quick]]
// Defaults: 1920 1080 5 spheres_on_mirror 0.3 4; "native": the native traces alone (profiling),
// "quick": those without the march and the texel experiments (comparing builds).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "native_mirror_trace.hpp"
#include "scenes/analytic_scene.hpp"
#include "ssrcl/ssrcl.hpp"

namespace {

using ssrcl::bench::NativeMirrorTrace;
using ssrcl::bench::TexelFormat;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

bool nativeOnly = false;
double openClTraceMs(ssrcl::Pipeline& p, long long& rays) {
  if (nativeOnly) return rays = 1, 1.0;
  p.execute();
  rays = p.stageTimes().tracedRays;
  return p.stageTimes().ms.at("trace");
}

void printNative(const char* what, double ms, const ssrcl::bench::PacketStats& s, int threads) {
  const int lanes = ssrcl::bench::packetLanes(ssrcl::bench::packetTraceIsa());
  // CPU time per step: what a step costs while the thread runs, whatever else the machine does.
  std::printf(
      "  %-28s %8.1f ms  %6.2f M rays/s (%5.2f on CPU time)  %5.1f steps/ray  %4.1f%% lanes live"
      "  %5.2f ns CPU/step  (%lld rays, %.1f%% hit; pyramid %.1f ms)\n",
      what, ms, s.rays / (ms * 1e3), s.rays * threads / (s.cpuMs * 1e3), double(s.laneSteps) / double(s.rays),
      100.0 * double(s.laneSteps) / (lanes * double(s.packetSteps)), s.cpuMs * 1e6 / double(s.laneSteps), s.rays,
      100.0 * double(s.hits) / double(s.rays), s.pyramidMs);
}

}  // namespace

int main(int argc, char** argv) {
  const int w = argc > 2 ? std::atoi(argv[1]) : 1920, h = argc > 2 ? std::atoi(argv[2]) : 1080;
  const int rounds = argc > 3 ? std::atoi(argv[3]) : 5;
  const std::string sceneName = argc > 4 ? argv[4] : "spheres_on_mirror";
  const float roughness = argc > 5 ? float(std::atof(argv[5])) : 0.3f;
  const int samples = argc > 6 ? std::atoi(argv[6]) : 4;
  const std::string mode = argc > 7 ? argv[7] : "";
  nativeOnly = mode == "native" || mode == "quick";
  if (!ssrcl::bench::packetTraceSupported()) {
    std::fprintf(stderr, "ssrcl_trace_roofline: the packet trace needs a CPU with AVX2 (x86-64-v3) or AVX-512\n");
    return 1;
  }
  const int threads = int(std::max(1u, std::thread::hardware_concurrency()));
  const ssrcl::scenes::Scene scene = ssrcl::scenes::makeScene(sceneName);
  const ssrcl::Camera camera = ssrcl::scenes::makeCamera(scene.view, w, h);
  const ssrcl::GBuffer mirrorFrame = ssrcl::scenes::renderGBuffer(scene, camera);
  ssrcl::GBuffer glossyFrame = mirrorFrame;
  std::fill(glossyFrame.roughness.data.begin(), glossyFrame.roughness.data.end(), roughness);

  const ssrcl::TraceSettings mirrorSettings = ssrcl::bench::nativeMirrorSettings();
  ssrcl::TraceSettings glossySettings = mirrorSettings;  // the default's rays, constant 1% thickness
  glossySettings.constantRoughness.reset();
  glossySettings.samplesPerPixel = samples;
  ssrcl::Device device(ssrcl::DeviceType::CPU);
  ssrcl::Pipeline clMirror(device), clGlossy(device);
  clMirror.setGBuffer(mirrorFrame);
  clMirror.setCamera(camera);
  clMirror.settings() = mirrorSettings;
  clMirror.commit();
  clGlossy.setGBuffer(glossyFrame);
  clGlossy.setCamera(camera);
  clGlossy.settings() = glossySettings;
  clGlossy.commit();
  NativeMirrorTrace mirror(mirrorFrame, camera, mirrorSettings), glossy(glossyFrame, camera, glossySettings);
  mirror.run(threads);  // setup (and the scalar trace, once)
  glossy.run(threads);
  long long clMirrorRays = 0, clGlossyRays = 0;
  openClTraceMs(clMirror, clMirrorRays);  // warm-up: kernel builds, first touch
  openClTraceMs(clGlossy, clGlossyRays);
  mirror.runPackets(threads);
  glossy.runGlossyPackets(threads, samples);

  std::vector<double> clM, clG, natM, natG;
  ssrcl::bench::PacketStats mirrorStats, glossyStats;
  for (int r = 0; r < rounds; ++r) {
    clM.push_back(openClTraceMs(clMirror, clMirrorRays));
    natM.push_back(mirror.runPackets(threads));
    mirrorStats = mirror.packetStats();
    clG.push_back(openClTraceMs(clGlossy, clGlossyRays));
    natG.push_back(glossy.runGlossyPackets(threads, samples));
    glossyStats = glossy.packetStats();
    std::printf("round %d: mirror OpenCL %.1f native %.1f ms (ratio %.1f); glossy OpenCL %.1f native %.1f ms"
                " (per ray %.1f)\n", r + 1, clM.back(), natM.back(), clM.back() / natM.back(), clG.back(), natG.back(),
                (clG.back() / clGlossyRays) / (natG.back() / glossyStats.rays));
  }
  const ssrcl::bench::PacketIsa isa = ssrcl::bench::packetTraceIsa();
  std::printf("%s %dx%d, %d threads, medians of %d rounds (native: ray generation + trace, %d-lane %s packets)\n",
              sceneName.c_str(), w, h, threads, rounds, ssrcl::bench::packetLanes(isa),
              ssrcl::bench::packetIsaName(isa));
  std::printf("  OpenCL trace stage, mirror    %8.1f ms  %6.2f M rays/s  (%lld rays)\n", median(clM),
              clMirrorRays / (median(clM) * 1e3), clMirrorRays);
  printNative("native min-max, mirror", median(natM), mirrorStats, threads);
  std::printf("  OpenCL trace stage, glossy    %8.1f ms  %6.2f M rays/s  (%lld rays)\n", median(clG),
              clGlossyRays / (median(clG) * 1e3), clGlossyRays);
  printNative("native min-max, glossy", median(natG), glossyStats, threads);
  // The OpenCL trace's work per ray, counted in a run apart after the timed rounds (counting slows
  // it; the pipelines are not timed again, so they stay in counting mode).
  if (!nativeOnly) {
    for (auto [p, what] : {std::pair{&clMirror, "mirror"}, std::pair{&clGlossy, "glossy"}}) {
      p->settings().countWork = true;
      p->commit();
      p->execute();
      std::printf("  OpenCL %s: %.1f texel reads/ray\n", what,
                  double(p->stageTimes().depthFetches) / double(std::max(1LL, p->stageTimes().tracedRays)));
    }
  }
  std::printf("  OpenCL / native per ray: mirror %.1f, glossy %.1f\n",
              (median(clM) / clMirrorRays) / (median(natM) / mirrorStats.rays),
              (median(clG) / clGlossyRays) / (median(natG) / glossyStats.rays));

  if (mode == "quick") return 0;
  mirror.runLinearMarch(threads);
  const ssrcl::bench::HitAgreement agree =
      ssrcl::bench::compareHitPoints(mirror.packetHitPoints(), mirror.linearHitPoints(), 0.01f);
  std::printf("  mirror hits equal to the half-pixel march on %.4f%% of %lld rays (%lld of %lld hit pixels differ)\n",
              100.0 * double(mirrorStats.rays - agree.disagreeing) / double(mirrorStats.rays), mirrorStats.rays,
              agree.disagreeing, agree.hitPixels);

  // What bounds it: the same rays with 8-byte texels, and with no texel loads at all.
  for (const auto& [format, name] : {std::pair{TexelFormat::Float, "mirror, 8-byte float texels"},
                                     std::pair{TexelFormat::NoMemory, "mirror, no texel loads"},
                                     std::pair{TexelFormat::Half, "mirror, 4-byte texels again"}}) {
    mirror.setPacketTexels(format);
    std::vector<double> ms;
    for (int r = 0; r < rounds; ++r) ms.push_back(mirror.runPackets(threads));
    printNative(name, median(ms), mirror.packetStats(), threads);
  }
  return 0;
}
