// Reads a G-code program from a string with the installed netshape and prints its summary.
#include <cstdio>
#include <exception>

#include <netshape/toolpath.hpp>

int main() {
  const char* program =
      "(square with rounded corners, mm)\n"
      "G21 G90 G17 F600\n"
      "G0 X0 Y0 Z5\n"
      "G1 Z-1\n"
      "G1 X20\n"
      "G3 X25 Y5 R5\n"
      "G1 Y20\n"
      "G2 X30 Y25 I5 J0\n"
      "M2\n";
  try {
    const netshape::toolpath::Summary s = netshape::toolpath::summarize_gcode_text(program, "consumer");
    std::printf("blocks %ld (rapid %ld, line %ld, arc %ld)\n", s.blocks(), s.rapids, s.lines, s.arcs);
    std::printf("feed_length_mm %.6f\nfeed_time_s %.6f\n", s.feed_length, s.feed_time);
    std::printf("bbox_mm %.3f %.3f %.3f .. %.3f %.3f %.3f\n", s.bbox_min.x(), s.bbox_min.y(), s.bbox_min.z(),
                s.bbox_max.x(), s.bbox_max.y(), s.bbox_max.z());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 2;
  }
  return 0;
}
