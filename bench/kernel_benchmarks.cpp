// Google Benchmark of single stages on a generated 1920x1080 scene, timed by OpenCL profiling
// events (manual time), so a kernel change can be measured in isolation:
//   build/bench/ssrcl_kernel_benchmarks --benchmark_filter=Trace
#include <benchmark/benchmark.h>

#include "scenes/analytic_scene.hpp"
#include "ssrcl/ssrcl.hpp"

namespace {

struct Frame {
  ssrcl::Camera camera;
  ssrcl::GBuffer gbuffer;
};

const Frame& frame() {
  static const Frame f = [] {
    const ssrcl::scenes::Scene s = ssrcl::scenes::makeScene("spheres_on_mirror");
    Frame out;
    out.camera = ssrcl::scenes::makeCamera(s.view, 1920, 1080);
    out.gbuffer = ssrcl::scenes::renderGBuffer(s, out.camera);
    return out;
  }();
  return f;
}

// Runs the pipeline `settings` and reports `stage`'s device time per iteration.
void runStage(benchmark::State& state, const char* stage, ssrcl::TraceSettings settings) {
  static ssrcl::Device device(ssrcl::DeviceType::Default);
  const Frame& f = frame();
  ssrcl::Pipeline p(device);
  p.setGBuffer(f.gbuffer);
  p.setCamera(f.camera);
  p.settings() = settings;
  p.commit();
  p.execute();  // warm-up
  for (auto _ : state) {
    p.execute();
    state.SetIterationTime(p.stageTimes().ms.at(stage) * 1e-3);
  }
  state.counters["rays"] = double(p.stageTimes().tracedRays);
}

void HzbBuild(benchmark::State& state) {
  ssrcl::TraceSettings s;
  s.maxRoughness = 0.0f;  // no ray: the pyramid alone
  s.constantRoughness = 1.0f;
  runStage(state, "hzb", s);
}

void TraceMirror(benchmark::State& state) {
  ssrcl::TraceSettings s;
  s.tracer = static_cast<ssrcl::Tracer>(state.range(0));
  runStage(state, "trace", s);
}

void TraceGlossy(benchmark::State& state) {
  ssrcl::TraceSettings s;
  s.tracer = static_cast<ssrcl::Tracer>(state.range(0));
  s.constantRoughness = 0.3f;
  runStage(state, "trace", s);
}

// Arguments: 0 Hi-Z, 1 linear, 2 DDA (ssrcl::Tracer's order).
BENCHMARK(HzbBuild)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(TraceMirror)->Arg(0)->Arg(1)->Arg(2)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(TraceGlossy)->Arg(0)->Arg(1)->Arg(2)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
