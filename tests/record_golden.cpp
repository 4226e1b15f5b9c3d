// Writes the golden digests (tests/golden/runs.txt run with a given `ssrcl` binary) to a file:
//   ssrcl_record_golden <ssrcl> <source dir> <out file>
// scripts/record-golden.sh builds a revision's CLI and calls this.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "support/golden_runs.hpp"
#include "support/temp_dir.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: ssrcl_record_golden <ssrcl binary> <source dir> <out file>\n";
    return 2;
  }
  try {
    const std::string cli = argv[1], source = argv[2];
    const ssrcl::test::TempDir work;
    std::ofstream out(argv[3]);
    out << "# Digests of `ssrcl trace` outputs (tests/golden/runs.txt); scripts/record-golden.sh\n"
        << ssrcl::test::goldenDeviceLine(cli) << "\n";
    for (const auto& run : ssrcl::test::readGoldenRuns(source + "/tests/golden/runs.txt")) {
      const std::string line = ssrcl::test::goldenDigest(cli, run, source, work.path().string());
      std::cout << line << std::endl;
      out << line << "\n";
    }
    if (!out) throw std::runtime_error(std::string(argv[3]) + ": cannot write");
  } catch (const std::exception& e) {
    std::cerr << "ssrcl_record_golden: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
