// Reading back how an EXR was written: what `ssrcl batch` compares before it resumes a shot.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <stdexcept>

#include "ssrcl/error.hpp"
#include "ssrcl/exr_output.hpp"

namespace ssrcl {

ExrDescription describeExr(const std::string& path) {
  try {
    const Imf::Header header = Imf::MultiPartInputFile(path.c_str()).header(0);
    ExrDescription d;
    const std::vector<std::string>& names = exrCompressionNames();
    const std::size_t index = std::size_t(header.compression());
    d.compression = index < names.size() ? names[index] : "unknown";
    for (auto c = header.channels().begin(); c != header.channels().end(); ++c)
      d.channelIsHalf[c.name()] = c.channel().type == Imf::HALF;
    for (auto a = header.begin(); a != header.end(); ++a)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a.attribute())) d.stringAttributes[a.name()] = s->value();
    return d;
  } catch (const std::exception& e) {  // Iex::BaseExc derives from std::exception
    throw Error(ErrorCode::IoError, path + ": cannot read its header (" + e.what() + ")");
  }
}

}  // namespace ssrcl
