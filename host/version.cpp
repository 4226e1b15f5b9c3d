#include "ssrcl/version.hpp"

namespace ssrcl {

int versionNumber() noexcept { return SSRCL_VERSION_NUMBER; }
const char* versionString() noexcept { return SSRCL_VERSION; }

}  // namespace ssrcl
