#pragma once
#include <Imath/ImathBox.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfPixelType.h>

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ssrcl::test {

// One channel: full name, values row by row over the data window (top row first), and the type
// it is stored as (HALF rounds, UINT truncates and needs values >= 0; see storedValue).
struct ExrChannel {
  std::string name;
  std::vector<float> values;
  Imf::PixelType type = Imf::FLOAT;
};

struct ExrPart {
  std::string name;  // part name attribute; required by OpenEXR when a file has several parts
  std::vector<ExrChannel> channels;
};

struct ExrOptions {
  Imf::Compression compression = Imf::ZIP_COMPRESSION;
  bool tiled = false;
  int tileSize = 4;              // square tiles, one level
  int originX = 0, originY = 0;  // data window origin; the display window stays at (0, 0)...
  std::optional<Imath::Box2i> displayWindow;      // ...unless given here
  std::function<void(Imf::Header&)> editHeader;  // adds attributes (cameras) to each part's header
};

// A single-part file, with no part name, as most renderers write it.
void writeExr(const std::string& path, int width, int height, const std::vector<ExrChannel>& channels,
              const ExrOptions& options = {});
// A multi-part file; every part gets the same size and options.
void writeMultiPartExr(const std::string& path, int width, int height, const std::vector<ExrPart>& parts,
                       const ExrOptions& options = {});

// Everything in a single-part file, read as float, with the stored type of each channel.
struct ExrContents {
  int width = 0, height = 0;
  Imath::Box2i dataWindow, displayWindow;
  Imf::Compression compression = Imf::NO_COMPRESSION;
  std::map<std::string, ExrChannel> channels;
};
ExrContents readExr(const std::string& path);

// The value a channel of `type` gives back after `value` was written to it.
float storedValue(Imf::PixelType type, float value);

// width * height distinct, non-round values, so a misplaced pixel or channel shows.
std::vector<float> pattern(int width, int height, float seed);

// A string attribute of a file's (first part's) header, e.g. ssrcl's "ssrcl/settings" record.
// Throws where the file has none of that name.
std::string stringAttribute(const std::string& path, const char* name);

// Whole-file byte access, for corrupting files.
std::string readBytes(const std::string& path);
void writeBytes(const std::string& path, const std::string& bytes);

}  // namespace ssrcl::test
