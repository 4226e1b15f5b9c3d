#include <cctype>

#include "ssrcl/device.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl {

Device openDevice(const std::string& option) {
  if (option.empty() || option == "default") return Device(DeviceType::Default);
  if (option == "cpu") return Device(DeviceType::CPU);
  if (option == "gpu") return Device(DeviceType::GPU);
  bool digits = option.size() < 6;
  for (char c : option) digits = digits && std::isdigit(static_cast<unsigned char>(c));
  if (!digits)
    throw Error(ErrorCode::InvalidArgument, "--device: expected an index, cpu, gpu or default, got '" + option + "'");
  return Device(std::stoi(option));
}

}  // namespace ssrcl
