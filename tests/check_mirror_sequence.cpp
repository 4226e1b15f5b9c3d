// Checks the outputs of a batch run (`ssrcl batch`, the Slurm array job) over a mirror shot that
// ssrcl_make_sequence wrote, traced with --edge-fade 0, against each frame's exact reflections:
//   ssrcl_check_mirror_sequence OUT_DIR FRAMES WIDTH HEIGHT [FIRST=1001]
// reads OUT_DIR/shot.<frame>.refl.exr; prints each frame's match; exits 1 when one is below the
// floor (support/mirror_pass_match.hpp), 2 on bad arguments or unreadable outputs.
#include <cstdlib>
#include <exception>
#include <iostream>

#include "support/analytic_sequence.hpp"
#include "support/mirror_pass_match.hpp"

int main(int argc, char** argv) {
  if (argc < 5) {
    std::cerr << "usage: ssrcl_check_mirror_sequence OUT_DIR FRAMES WIDTH HEIGHT [FIRST=1001]\n";
    return 2;
  }
  using namespace ssrcl::test;
  AnalyticSequence s;  // as ssrcl_make_sequence writes it
  s.frameCount = std::atoi(argv[2]);
  s.width = std::atoi(argv[3]);
  s.height = std::atoi(argv[4]);
  if (argc > 5) s.firstFrame = std::atoi(argv[5]);
  bool ok = s.frameCount > 0;
  try {
    for (int i = 0; i < s.frameCount; ++i) {
      const std::string output = std::string(argv[1]) + "/" + s.prefix + "." + std::to_string(s.firstFrame + i) + ".refl.exr";
      const MirrorPassMatch m = matchExactReflections(output, sequenceScene(s), sequenceCamera(s, i));
      const bool good = m.visibleRate() >= kMirrorPassFloor && m.missedRate() >= kMirrorPassFloor;
      std::cout << output << ": visible hits matched " << m.visibleRate() << " of " << m.visible << ", misses "
                << m.missedRate() << " of " << m.missed << (good ? "" : "  BELOW THE FLOOR") << "\n";
      ok = ok && good;
    }
  } catch (const std::exception& e) {
    std::cerr << "ssrcl_check_mirror_sequence: " << e.what() << "\n";
    return 2;
  }
  return ok ? 0 : 1;
}
