// The device copy bench/ssrcl_roofline sets the HZB against (bench/device_copy_time): it runs on
// the device the pipeline uses, and a device it cannot find is named in the error, not replaced.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "device_copy_time.hpp"
#include "support/test_device.hpp"

namespace {

TEST(DeviceCopyTime, TimesACopyOnTheTestDevice) {
  ssrcl::bench::DeviceCopyTime copy(ssrcl::test::testDevice().info(), size_t(1) << 22);
  const double ms = copy.run();
  EXPECT_TRUE(std::isfinite(ms));
  EXPECT_GT(ms, 0.0);
}

TEST(DeviceCopyTime, AnUnknownDeviceIsNamedInTheError) {
  ssrcl::DeviceInfo info = ssrcl::test::testDevice().info();
  info.name = "no such device";
  try {
    ssrcl::bench::DeviceCopyTime copy(info, 1024);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'no such device'"), std::string::npos) << e.what();
  }
}

}  // namespace
