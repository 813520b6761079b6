// A CAM plugin's use of netshape: compensate a G-code program for the geometric errors of a machine
// (volumetric compensation, Yang & Kweon §4.2) and write the compensated program. The machine here
// is built in code (an X positioning error, a Y straightness, an XY squareness); a plugin would fill
// netshape::machine::Machine from its own machine data. Usage: consumer_compensate [program.ngc]
// (without an argument a small built-in program is used); the program goes to stdout, the report to
// stderr. Exit 2 with one line on stderr for bad input.
#include <cstdio>
#include <exception>
#include <iostream>

#include <netshape/compensation.hpp>
#include <netshape/machine.hpp>
#include <netshape/toolpath.hpp>

namespace ns = netshape;

int main(int argc, char** argv) {
  const char* builtin =
      "(pocket wall)\n"
      "G21 G90 G17\n"
      "T1 M6\n"
      "S8000 M3\n"
      "G0 X-100 Y-50 Z5\n"
      "G1 Z0 F600\n"
      "G1 X150\n"
      "G3 X200 Y0 R50\n"
      "G1 Y120\n"
      "M30\n";
  try {
    // machine: X and Y carry the tool, Z the table; tool 100 mm long; errors as ISO 230-1 components
    ns::machine::Machine m = ns::machine::ideal_machine({0, 1}, {2}, 100.0);
    m.name = "plugin demo";
    m.axes[0].errors[0] = ns::machine::ErrorFunction::polynomial({0.01, 2e-4});  // EXX [mm]
    m.axes[1].errors[0] = ns::machine::ErrorFunction::polynomial({0.0, 3e-5});   // EXY [mm]
    m.ec0y = 5e-5;                                                                // EC0Y [rad]
    m.validate();

    const ns::toolpath::Toolpath program = argc > 1 ? ns::toolpath::read_gcode(argv[1])
                                                    : ns::toolpath::parse_gcode(builtin, "builtin.ngc");
    ns::compensation::ProgramOptions options;
    options.chord_tolerance = 0.001;  // [mm]
    const ns::compensation::ProgramResult r = ns::compensation::compensate_program(m, program, options);

    ns::toolpath::WriterOptions w;
    w.header_comment = "compensated for " + m.name;
    ns::toolpath::write_gcode(r.toolpath, std::cout, w);
    std::fprintf(stderr,
                 "blocks %ld -> %ld, arcs kept %ld, arcs split %ld, max correction %.6f mm, "
                 "max residual %.3g mm, max path deviation %.6f mm\n",
                 r.report.blocks_in, r.report.blocks_out, r.report.arcs_kept, r.report.arcs_split,
                 r.report.max_correction, r.report.max_residual, r.report.max_path_deviation);
    return r.report.max_path_deviation <= options.chord_tolerance ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer_compensate: %s\n", e.what());
    return 2;
  }
}
