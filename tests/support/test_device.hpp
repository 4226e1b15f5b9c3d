#pragma once
#include <cstdlib>
#include <string>

#include "ssrcl/device.hpp"

namespace ssrcl::test {

// The device tests run on: PoCL's CPU by default (what CI has); SSRCL_TEST_DEVICE=gpu or an
// index from `ssrcl devices` runs the same suite on another device.
inline Device testDevice() {
  const char* env = std::getenv("SSRCL_TEST_DEVICE");
  std::string choice = env ? env : "cpu";
  if (choice == "cpu") return Device(DeviceType::CPU);
  if (choice == "gpu") return Device(DeviceType::GPU);
  return Device(std::stoi(choice));
}

// That device, opened once per test program (a PoCL device costs a second to open).
inline Device& sharedTestDevice() {
  static Device d = testDevice();
  return d;
}

}  // namespace ssrcl::test
