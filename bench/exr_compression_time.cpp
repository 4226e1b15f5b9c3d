// Writes an EXR's channels (as float, the pass's type) with each lossless compression OpenEXR
// offers and reads them back, on OpenEXR's global pool as `ssrcl` sets it (a thread a core):
// median write and read milliseconds and the file's size, to choose the pass's default
// compression (docs/BENCHMARKS.md "The pass's compression").
//
//   ssrcl_exr_compression PASS.exr [REPETITIONS]
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfThreading.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Every channel of a file as float planes.
struct Planes {
  std::vector<std::string> names;
  std::vector<std::vector<float>> data;
  Imf::FrameBuffer buffer;
};

void readInto(const char* path, Planes& planes) {
  Imf::InputFile in(path);
  const Imath::Box2i& w = in.header().dataWindow();
  const size_t width = size_t(w.max.x - w.min.x + 1), height = size_t(w.max.y - w.min.y + 1);
  if (planes.names.empty())
    for (auto c = in.header().channels().begin(); c != in.header().channels().end(); ++c)
      planes.names.push_back(c.name());
  planes.data.assign(planes.names.size(), std::vector<float>(width * height));
  planes.buffer = Imf::FrameBuffer();
  for (size_t k = 0; k < planes.names.size(); ++k)
    planes.buffer.insert(planes.names[k], Imf::Slice::Make(Imf::FLOAT, planes.data[k].data(), w, sizeof(float),
                                                           sizeof(float) * width));
  in.setFrameBuffer(planes.buffer);
  in.readPixels(w.min.y, w.max.y);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s PASS.exr [REPETITIONS]\n", argv[0]);
    return 2;
  }
  const int repetitions = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
  Imf::setGlobalThreadCount(int(std::thread::hardware_concurrency()));
  Planes pass;
  readInto(argv[1], pass);
  Imf::Header header = Imf::InputFile(argv[1]).header();
  for (auto c = header.channels().begin(); c != header.channels().end(); ++c) c.channel().type = Imf::FLOAT;
  const std::string written = std::filesystem::temp_directory_path() / "ssrcl_exr_compression.exr";
  const Imath::Box2i& w = header.dataWindow();

  std::printf("compression  write ms  read ms  MB     pixels\n");
  const std::pair<Imf::Compression, const char*> kinds[] = {{Imf::NO_COMPRESSION, "none"},
                                                            {Imf::RLE_COMPRESSION, "rle"},
                                                            {Imf::ZIPS_COMPRESSION, "zips"},
                                                            {Imf::ZIP_COMPRESSION, "zip"},
                                                            {Imf::PIZ_COMPRESSION, "piz"}};
  for (const auto& [compression, name] : kinds) {
    header.compression() = compression;
    std::vector<double> writeMs, readMs;
    bool same = true;
    for (int r = 0; r < repetitions; ++r) {
      Clock::time_point start = Clock::now();
      {
        Imf::OutputFile out(written.c_str(), header);
        out.setFrameBuffer(pass.buffer);
        out.writePixels(w.max.y - w.min.y + 1);
      }
      writeMs.push_back(msSince(start));
      Planes back;
      back.names = pass.names;
      start = Clock::now();
      readInto(written.c_str(), back);
      readMs.push_back(msSince(start));
      same = same && back.data == pass.data;
    }
    std::printf("%-11s  %8.0f  %7.0f  %5.1f  %s\n", name, median(writeMs), median(readMs),
                double(std::filesystem::file_size(written)) / 1e6, same ? "same" : "DIFFER");
  }
  std::filesystem::remove(written);
  return 0;
}
