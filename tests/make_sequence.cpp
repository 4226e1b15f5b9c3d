// Writes a generated shot for batch tests and benchmarks (see support/analytic_sequence.hpp):
//   ssrcl_make_sequence DIR [FRAMES] [WIDTH] [HEIGHT] [ROUGHNESS] [FIRST]
// Prints the frame pattern, e.g. DIR/shot.####.exr.
#include <cstdlib>
#include <iostream>

#include "support/analytic_sequence.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: ssrcl_make_sequence DIR [FRAMES=8] [WIDTH=64] [HEIGHT=36] [ROUGHNESS=-1] [FIRST=1001]\n";
    return 2;
  }
  ssrcl::test::AnalyticSequence s;
  s.directory = argv[1];
  if (argc > 2) s.frameCount = std::atoi(argv[2]);
  if (argc > 3) s.width = std::atoi(argv[3]);
  if (argc > 4) s.height = std::atoi(argv[4]);
  if (argc > 5) s.roughness = std::atof(argv[5]);
  if (argc > 6) s.firstFrame = std::atoi(argv[6]);
  try {
    std::cout << ssrcl::test::writeAnalyticSequence(s) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "ssrcl_make_sequence: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
