#include <OpenEXR/ImfThreading.h>

#include "ssrcl/io.hpp"

namespace ssrcl {

// OpenEXR 3.1 hands a file's chunks to its global pool only; with none (its default) each file
// is (de)compressed on the calling thread alone.
void setExrThreads(int count) { Imf::setGlobalThreadCount(count < 0 ? 0 : count); }

}  // namespace ssrcl
