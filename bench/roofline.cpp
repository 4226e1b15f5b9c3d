#include "roofline.hpp"

#include <algorithm>
#include <iomanip>
#include <thread>

#include "device_copy_time.hpp"
#include "device_frame_stages.hpp"
#include "native_mirror_trace.hpp"
#include "packet_hiz_trace.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::cli {
RooflineResult runRoofline(const Device& device, const BenchInput& input, int repetitions) {
  const TraceSettings settings = bench::nativeMirrorSettings();
  Pipeline p(device);
  p.setGBuffer(input.gbuffer);
  p.setCamera(input.camera);
  p.settings() = settings;
  p.commit();
  bench::NativeMirrorTrace native(input.gbuffer, input.camera, settings);
  // The stages before the trace, each timed apart, with the adaptive thickness model (the
  // default; the trace's rays above take the constant one, which has no stage of its own).
  TraceSettings frameSettings = settings;
  frameSettings.thicknessModel = ThicknessModel::Adaptive;
  bench::DeviceFrameStages deviceFrame(device, input.gbuffer, input.camera, frameSettings);
  bench::NativeMirrorTrace nativeFrame(input.gbuffer, input.camera, frameSettings);
  bench::DeviceCopyTime depthCopy(device.info(), size_t(input.camera.width) * input.camera.height * sizeof(float));
  RooflineResult r;
  r.input = input.name;
  r.width = input.camera.width;
  r.height = input.camera.height;
  r.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  r.stages = {"setup", "hzb", "thickness", "range pyramid", "colour pyramid", "trace"};
  const size_t stages = r.stages.size();
  p.execute();  // warm-up: kernel compilation, first touch
  native.run(r.threads);
  deviceFrame.run();
  nativeFrame.runFrame(r.threads);
  const auto frameMs = [](const bench::FrameStageMs& f) {
    return std::vector<double>{f.setup, f.hzb, f.thickness, f.rangePyramid, f.colorPyramid};
  };
  std::vector<std::vector<double>> cl(stages), nat(stages);
  std::vector<double> copy, packets;
  r.packets = bench::packetTraceSupported();
  // Alternating, so both see the same load on a shared machine.
  for (int k = 0; k < repetitions; ++k) {
    const std::vector<double> clFrame = frameMs(deviceFrame.run()), natFrame = frameMs(nativeFrame.runFrame(r.threads));
    for (size_t s = 0; s < clFrame.size(); ++s) {
      cl[s].push_back(clFrame[s]);
      nat[s].push_back(natFrame[s]);
    }
    p.execute();
    const auto& ms = p.stageTimes().ms;
    cl[stages - 1].push_back(ms.count("trace") ? ms.at("trace") : 0.0);
    nat[stages - 1].push_back(native.run(r.threads).trace);
    if (r.packets) packets.push_back(native.runPackets(r.threads));
    copy.push_back(depthCopy.run());
  }
  for (size_t s = 0; s < stages; ++s) {
    r.opencl.push_back(stageStats(cl[s]));
    r.native.push_back(stageStats(nat[s]));
  }
  r.depthCopy = stageStats(copy);
  r.rays = native.rays();
  r.hits = bench::compareHitDistances(native.distance(), p.output("distance").data);
  if (r.packets) {
    r.packetTrace = stageStats(packets);
    // The packet trace tests depth alone: its reference is the half-pixel march, not the plane test.
    native.runLinearMarch(r.threads);
    r.packetHits = bench::compareHitPoints(native.packetHitPoints(), native.linearHitPoints(), 0.01f);
  }
  return r;
}

namespace {
double agreedPercent(const bench::HitAgreement& h) {
  return h.hitPixels ? 100.0 * (h.hitPixels - h.disagreeing) / h.hitPixels : 100.0;
}
}  // namespace

void printRoofline(std::ostream& out, const std::vector<RooflineResult>& results) {
  out << "\nNative roofline (median ms; the stages before the trace each apart, with the adaptive thickness;\n"
      << "the trace: mirror rays of every reflecting pixel, constant thickness, Hi-Z):\n";
  for (const RooflineResult& r : results) {
    out << "  " << r.input << " " << r.width << "x" << r.height << ", " << r.rays << " rays, native on "
        << r.threads << " threads\n";
    for (size_t s = 0; s < r.stages.size(); ++s) {
      const double cl = r.opencl[s].medianMs, nat = r.native[s].medianMs;
      out << "    " << std::left << std::setw(14) << r.stages[s] << std::right << std::fixed << std::setprecision(2)
          << "  OpenCL " << std::setw(9) << cl << "  native " << std::setw(9) << nat << "  OpenCL / native "
          << std::setprecision(2) << (nat > 0 ? cl / nat : 0.0);
      if (r.stages[s] == "hzb")
        out << "  (device copy of the depth buffer " << std::setprecision(2) << r.depthCopy.medianMs
            << " ms, hzb / copy " << (r.depthCopy.medianMs > 0 ? cl / r.depthCopy.medianMs : 0.0) << ")";
      if (r.stages[s] == "trace")
        out << "  (" << std::setprecision(1) << r.rays / (cl * 1e3) << " vs " << r.rays / (nat * 1e3)
            << " Mrays/s)";
      out << "\n";
    }
    out << "    hits agree on " << std::setprecision(4) << agreedPercent(r.hits) << "% of " << r.hits.hitPixels
        << " pixels hit by either\n";
    const double cl = r.opencl.back().medianMs, scalar = r.native.back().medianMs, simd = r.packetTrace.medianMs;
    if (!r.packets) {
      out << "    SIMD native: not run (needs AVX2 or AVX-512)\n";
      continue;
    }
    const bench::PacketIsa isa = bench::packetTraceIsa();
    out << "    trace, SIMD native (min-max Hi-Z, " << bench::packetLanes(isa) << "-ray " << bench::packetIsaName(isa)
        << " packets) " << std::setprecision(2) << simd << " ms (" << std::setprecision(1) << r.rays / (simd * 1e3)
        << " Mrays/s)  OpenCL / SIMD native " << std::setprecision(2) << (simd > 0 ? cl / simd : 0.0)
        << "  scalar / SIMD native " << (simd > 0 ? scalar / simd : 0.0) << "\n";
    out << "    SIMD native hits equal to a half-pixel march of the depth on " << std::setprecision(4) << agreedPercent(r.packetHits) << "% of "
        << r.packetHits.hitPixels << " pixels hit by either\n";
  }
}

}  // namespace ssrcl::cli
