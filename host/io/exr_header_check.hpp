#pragma once
#include <string>

namespace ssrcl {

// Refuses an EXR whose header declares more than the file can hold before OpenEXR allocates it
// (see host/io/exr_gbuffer.cpp). Throws Error(IoError) naming the file; leaves files without the
// EXR magic number to OpenEXR.
void checkHeaderSizes(const std::string& path);

}  // namespace ssrcl
