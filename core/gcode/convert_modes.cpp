// Steps 11-19 of a block's execution: the modes a block sets (plane, units, cutter
// compensation, tool length offset, coordinate system, path control, distance and retract modes)
// and the non-modal codes of group 0 (G28/G30, G10, G92).
#include "interpreter_impl.hpp"

#include <cmath>

#include "codes.hpp"

namespace ncjoule::detail {

// 11. Plane, 12. units.
void Interpreter::convert_plane_and_units(const BlockValues& v) {
  for (int code : v.g) {
    Plane p = state_.plane;
    if (code == 170) p = Plane::XY;
    if (code == 180) p = Plane::XZ;
    if (code == 190) p = Plane::YZ;
    if (p != state_.plane) state_.plane = p, emit_simple(CanonKind::PlaneSelect);
    if (code == 200 || code == 210) {
      const bool inch = code == 200;
      units_given_ = true;
      if (inch != state_.inch) {
        state_.inch = inch;
        emit_simple(CanonKind::LengthUnits);
      }
    }
  }
}

// 13. Cutter compensation.
void Interpreter::convert_cutter_compensation(const BlockValues& v) {
  for (int code : v.g) {
    if (code == 400) {
      cutter_comp_ = 40;
      comp_off(v.g_column(code));
    }
    if (code == 410 || code == 420 || code == 411 || code == 421 || code == 412 || code == 422) {
      cutter_comp_ = code;
      comp_on(v, code);
    }
  }
}

// 14. Tool length offset.
void Interpreter::convert_tool_length_offset(BlockValues& v) {
  for (int code : v.g) {
    double offset = tool_offset_z_;
    if (code == 430) {
      const int h = v.has('h') ? int(std::lround(*v['h'])) : state_.tool;
      auto it = tools_.find(h);
      offset = it != tools_.end() ? it->second.z_offset : 0.0;
      if (it == tools_.end() && h != 0 && !tools_.empty())
        warning(v.g_column(code), "tool " + std::to_string(h) + " is not in the tool table");
    } else if (code == 431) {
      offset = v.has('z') ? *v['z'] * unit() : 0.0;
      v.letter['z' - 'a'].reset();
    } else if (code == 490) {
      offset = 0;
    } else {
      continue;
    }
    // The program's Z stays where it was (as rs274 reports it); the offset shows on G53 moves.
    tool_offset_z_ = offset;
    CanonCommand c = make(CanonKind::ToolLengthOffset);
    c.value = offset;
    emit(std::move(c));
  }
}

// 15. Coordinate system.
void Interpreter::convert_coordinate_system(const BlockValues& v) {
  for (int code : v.g) {
    int index = 0;
    if (code >= 540 && code <= 590 && code % 10 == 0) index = (code - 530) / 10;
    if (code >= 591 && code <= 593) index = 6 + (code - 590);
    if (index) select_work_offset(index);
  }
}

// The Fanuc family's additional work offsets: Fanuc G54.1 P1-P300 (P1-P48 standard, the rest an
// option), Haas G154 P1-P99 and G110-G129 (= G154 P1-P20). They are work offsets 10 and up
// (9 + P); without a P, G54.1 and G154 take P1.
bool Interpreter::convert_additional_work_offset(int code, const BlockValues& v) {
  if (!dialect_.g65_macro_calls) return false;
  int p = 0;
  if (code == 541 || code == 1540) {
    p = v.has('p') ? int(std::lround(*v['p'])) : 1;
    if (p < 1 || p > kAdditionalWorkOffsets) {
      error(v.column['p' - 'a'], g_name(code) + " P" + number_text(*v['p']) +
                                     ": the additional work offsets are P1 to P" +
                                     std::to_string(kAdditionalWorkOffsets));
      return true;
    }
  } else if (code >= 1100 && code <= 1290 && code % 10 == 0) {
    p = (code - 1090) / 10;
  } else {
    return false;
  }
  select_work_offset(9 + p);
  return true;
}

void Interpreter::select_work_offset(int index) {
  const Pose old = g5x_[std::size_t(g5x_index_)], neu = g5x_[std::size_t(index)];
  pos_.x += old.x - neu.x, pos_.y += old.y - neu.y, pos_.z += old.z - neu.z;
  pos_.a += old.a - neu.a, pos_.b += old.b - neu.b, pos_.c += old.c - neu.c;
  g5x_index_ = index;
  params_.at(param::kCoordSystem) = index;
  CanonCommand c = make(CanonKind::WorkOffset);
  c.value = index;
  c.end = neu;
  emit(std::move(c));
}

// 16. Path control.
void Interpreter::convert_path_control(const BlockValues& v) {
  for (int code : v.g) {
    if (code == 610 || code == 611) {
      state_.path_mode = code == 610 ? PathMode::ExactPath : PathMode::ExactStop;
      state_.path_tolerance = 0;
      emit_simple(CanonKind::PathControl);
    } else if (code == 640) {
      state_.path_mode = PathMode::Continuous;
      state_.path_tolerance = v.has('p') ? *v['p'] * unit() : 0;
      // value: LinuxCNC's naive-CAM tolerance, Q, else P, else none (SET_NAIVECAM_TOLERANCE).
      naivecam_tolerance_ = v.has('q') ? *v['q'] * unit() : state_.path_tolerance;
      emit_simple(CanonKind::PathControl, naivecam_tolerance_);
    }
  }
}

// 17. Distance modes, 18. retract mode.
void Interpreter::convert_distance_modes(const BlockValues& v) {
  for (int code : v.g) {
    if (code == 900) incremental_ = false;
    if (code == 910) incremental_ = true;
    if (code == 901) arc_incremental_ = false;
    if (code == 911) arc_incremental_ = true;
    if (code == 980) retract_to_r_ = false;
    if (code == 990) retract_to_r_ = true;
  }
}

// 19. Home, coordinate data, axis offsets (non-modal group 0). True when the block's axis
// words were theirs, not a move's.
bool Interpreter::convert_group0(const BlockValues& v) {
  bool axes_used = false;
  for (int code : v.g) {
    switch (code) {
    case 280:
      go_home(v, param::kG28), axes_used = true;
      break;
    case 300:
      go_home(v, param::kG30), axes_used = true;
      break;
    case 281:
    case 301: {
      const int base = code == 281 ? param::kG28 : param::kG30;
      const Pose off = offset_total();
      params_.at(base) = pos_.x + off.x;
      params_.at(base + 1) = pos_.y + off.y;
      params_.at(base + 2) = pos_.z + off.z + tool_offset_z_;
      params_.at(base + 3) = pos_.a + off.a;
      params_.at(base + 4) = pos_.b + off.b;
      params_.at(base + 5) = pos_.c + off.c;
      break;
    }
    case 100:
      axes_used = true;
      if (v.has('l') && (std::lround(*v['l']) == 2 || std::lround(*v['l']) == 20))
        set_coordinate_data(v);
      else
        set_tool_data(v);
      break;
    case 920:
    case 921:
    case 922:
    case 923:
      if (code == 920) axes_used = true;
      set_axis_offsets(v);
      break;
    default:
      break;
    }
  }
  return axes_used;
}

} // namespace ncjoule::detail
