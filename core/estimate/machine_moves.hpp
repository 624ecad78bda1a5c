// Internal: the program's moves as the machine runs them, where it moves in machine coordinates.
//
// The interpreter follows rs274: a G53 move or a G28/G30 return goes to a machine position that
// the work offsets in its parameters turn into work coordinates. A profile or job file that gives
// the offsets ([setup] work_offsets_mm) seeds those parameters, and the moves land where they
// do on the machine. Where nothing gives them, every offset is zero and `G53 G0 Z0.` or
// `G91 G28 Z0.` would send the tool to the program's Z0, into the part, though on a Fanuc, Haas
// or Hurco they send it up to Z home. So without offsets a move that sends Z to a machine
// position ends at the machine's Z home, taken to be `z_home_above_work_mm` above the highest
// point the program reaches (and at least above its Z0), and the tool stays there until the
// program moves Z again. Such moves never cut and never size the default stock. A move that
// sends X or Y to a machine position goes where the profile's `xy_home_in_work_mm` puts machine
// X/Y home (Haas and Fusion posts end with `G53 G0 X.. Y0.` to bring the table forward);
// without it, to the machine coordinate read as a work coordinate, as rs274 does.
//
// The view also checks what only the machine's coordinates tell: a position past the travel
// limits (when offsets and limits are given; without offsets, a program whose own extent along
// an axis is longer than the machine's travel on it: `Y18` typed for `Y1.8` on 16 in of Y), and
// a switch between work offsets nothing describes (taken at one place: the time of the move
// between them is not known).
#pragma once

#include <array>
#include <map>
#include <optional>
#include <vector>

#include "ncjoule/gcode.hpp"
#include "ncjoule/machine.hpp"

namespace ncjoule::estimate_detail {

class MachineMoves {
public:
  // `offsets_given`: the work offsets are described (the interpreter's parameters hold them).
  // `home_z`: the work Z of the machine's Z home when they are not; none: above the highest
  // point seen so far (a first pass, still finding the program's highest point).
  MachineMoves(const WorkSetup& setup, bool offsets_given, std::optional<double> home_z,
               std::string file);

  // The command as the machine runs it (positions changed only without offsets).
  CanonCommand view(const CanonCommand& command);

  // What the view found to warn about, once each.
  std::vector<Diagnostic> take_diagnostics() { return std::move(diagnostics_); }

  // The work Z of Z home for the program's moves seen so far (all of them, after a first pass).
  double home_z() const;

private:
  void check_travel(const CanonCommand& move);
  // Without offsets: the program's own extent along each axis against the machine's travel.
  void check_extent(const CanonCommand& move);

  WorkSetup setup_;
  bool offsets_given_ = false;
  std::optional<double> home_z_; // fixed; none: follows highest_z_
  std::string file_;
  // An axis held at a machine position since a machine move (Z home; X/Y home where the
  // profile names it), until the program moves it again.
  struct Held {
    bool on = false;
    double programmed = 0; // where the interpreter thinks the axis is meanwhile
    double at = 0;         // where it is, in work coordinates (Z: home_z())
  };
  std::array<Held, 3> held_{};
  double highest_z_ = 0; // at least the program's Z0
  int first_offset_ = 0; // the first work offset the program selects (1 = G54)
  bool warned_offsets_ = false, warned_travel_ = false;
  // The lowest and highest work position each axis reaches (programmed, not machine moves).
  struct Extent {
    bool seen = false, warned = false;
    double low = 0, high = 0;
    int low_line = 0, high_line = 0; // 0-based lines where they were reached
  };
  std::array<Extent, 3> extent_{};
  Pose work_offset_{}, axis_offset_{};
  double tool_length_ = 0;
  std::vector<Diagnostic> diagnostics_;
};

} // namespace ncjoule::estimate_detail
