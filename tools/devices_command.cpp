#include <iomanip>
#include <iostream>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "ssrcl/device.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl::cli {

Action addDevicesCommand(CLI::App& app) {
  app.add_subcommand("devices", "List OpenCL devices; '*' marks the default");
  return [] {
    auto devices = Device::list();
    // With none found this throws NoDevice, whose message says why (exit 3).
    int def = Device(DeviceType::Default).info().index;
    for (const DeviceInfo& d : devices) {
      std::cout << (d.index == def ? "* " : "  ") << d.index << "  " << (d.isGpu ? "GPU" : "CPU") << "  " << d.name
                << "  [" << d.platform << ", " << d.version << ", " << d.computeUnits << " CU, " << std::fixed
                << std::setprecision(1) << d.globalMemory / 1073741824.0 << " GiB]\n";
    }
    return kExitOk;
  };
}

}  // namespace ssrcl::cli
