#include "linuxcnc_path.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace ncjoule::kinematics_detail::linuxcnc {
namespace {

constexpr double kUnlimited = std::numeric_limits<double>::infinity();

Vec3 xyz(const Pose& p) {
  return {p.x, p.y, p.z};
}

Vec3 axis_vector(int i, double value) {
  Vec3 v = Vec3::Zero();
  v[i] = value;
  return v;
}

// Plane axes of an arc as (first, second, normal) indices into x, y, z.
std::array<int, 3> plane_axes(Plane plane) {
  switch (plane) {
  case Plane::YZ:
    return {1, 2, 0};
  case Plane::XZ:
    return {2, 0, 1};
  default:
    return {0, 1, 2};
  }
}

bool moves_rotary(const CanonCommand& c) {
  return c.start.a != c.end.a || c.start.b != c.end.b || c.start.c != c.end.c;
}

// Does task wait for motion to finish before this command (emcTaskCheckPreconditions)?
bool empties_queue(CanonKind kind) {
  switch (kind) {
  case CanonKind::Dwell:
  case CanonKind::ChangeTool:
  case CanonKind::SpindleSpeed:
  case CanonKind::SpindleClockwise:
  case CanonKind::SpindleCounterClockwise:
  case CanonKind::SpindleStop:
  case CanonKind::MistOn:
  case CanonKind::MistOff:
  case CanonKind::FloodOn:
  case CanonKind::FloodOff:
  case CanonKind::ToolLengthOffset:
  case CanonKind::AxisOffset:
  case CanonKind::ProgramStop:
  case CanonKind::OptionalStop:
  case CanonKind::ProgramEnd:
  case CanonKind::Message:
    return true;
  default:
    return false;
  }
}

} // namespace

PathBuilder::PathBuilder(const Kinematics& machine, ItemWindow& items, ChargeSink sink)
    : machine_(machine), items_(items), sink_(std::move(sink)),
      naive_cam_([this](MergedLine&& line) { send(std::move(line)); }) {
  const auto& a = machine.axes;
  feed_bounds_ = {{a[0].accel_mm_s2, a[1].accel_mm_s2, a[2].accel_mm_s2},
                  {a[0].max_feed_mm_s, a[1].max_feed_mm_s, a[2].max_feed_mm_s}};
  rapid_bounds_ = {feed_bounds_.accel, {a[0].rapid_mm_s, a[1].rapid_mm_s, a[2].rapid_mm_s}};
}

void PathBuilder::move(std::size_t index, const CanonCommand& c, const MoveLimits* limits) {
  if ((c.kind == CanonKind::Feed || c.kind == CanonKind::Arc) &&
      naive_cam_.offer(index, c, naive_tolerance_))
    return;
  naive_cam_.flush();
  if (c.kind == CanonKind::Arc) {
    Segment s = circle_segment(c);
    apply_state(s, c);
    const double length = s.length;
    queue(std::move(s), {Member{index, length}});
    return;
  }
  send(MergedLine{c.start, c.end, &c, {Member{index, move_length(c)}}}, limits);
}

bool PathBuilder::event(const CanonCommand& c) {
  switch (c.kind) {
  case CanonKind::SetFeedRate:
    if (c.value != feed_rate_) naive_cam_.flush();
    feed_rate_ = c.value;
    return false;
  case CanonKind::SetFeedMode:
    naive_cam_.flush();
    return false;
  case CanonKind::PathControl:
    naive_cam_.flush();
    naive_tolerance_ = c.state.path_mode == PathMode::Continuous ? c.value : 0;
    if (c.text != "canned cycle") {
      path_mode_programmed_ = true;
      startup_tolerance_ = false;
    } else if (!path_mode_programmed_ && c.state.path_mode == PathMode::Continuous) {
      // A canned cycle restores the mode LinuxCNC's canon layer believes in: before any G61/G64
      // that is its start-up G64 P0.001 inch, which the planner itself did not have until now.
      startup_tolerance_ = true;
    }
    return false;
  case CanonKind::WorkOffset: {
    // The interpreter only re-sends an unchanged coordinate system; LinuxCNC's does not.
    const int index = static_cast<int>(std::lround(c.value));
    const Pose& o = c.end;
    if (index == work_index_ && o.x == work_offset_.x && o.y == work_offset_.y &&
        o.z == work_offset_.z && o.a == work_offset_.a && o.b == work_offset_.b &&
        o.c == work_offset_.c)
      return false;
    work_index_ = index;
    work_offset_ = o;
    stop();
    return true;
  }
  case CanonKind::SpindleClockwise:
  case CanonKind::SpindleCounterClockwise:
    stop();
    atspeed_next_feed_ = true;
    return true;
  case CanonKind::ProgramStop: // the operator's wait, not predicted
  case CanonKind::OptionalStop:
  case CanonKind::ProgramEnd:
    stop();
    return false;
  default:
    if (!empties_queue(c.kind)) return false;
    stop();
    return true;
  }
}

void PathBuilder::stop() {
  naive_cam_.flush();
  if (pending_) settle(std::nullopt, false, 0, 0, false); // never finalised: nor in LinuxCNC
  flowing_ = false;
}

void PathBuilder::send(MergedLine&& line, const MoveLimits* limits) {
  Segment s = line_segment(*line.last, line.start, line.end, limits);
  apply_state(s, *line.last);
  queue(std::move(s), std::move(line.members));
}

void PathBuilder::queue(Segment&& s, std::vector<Member>&& members) {
  if (pending_) {
    const AxisBounds& bounds = pending_->traverse && s.traverse ? rapid_bounds_ : feed_bounds_;
    Join j = join(*pending_, s, bounds);
    double cap = 0;
    switch (pending_->term) {
    case Term::Tangent:
      cap = pending_->kink_vel >= 0 ? pending_->kink_vel : kUnlimited;
      break;
    case Term::Parabolic:
      cap = j.parabolic_vel;
      break;
    default:
      break;
    }
    const bool continues = !members.empty() && !pending_members_.empty() &&
                           members.front().command == pending_members_.back().command;
    settle(std::move(j.blend), j.consumed, j.consumed_length, cap, continues);
  }
  pending_ = std::move(s);
  pending_members_ = std::move(members);
}

void PathBuilder::settle(std::optional<Segment> blend, bool consumed, double consumed_length,
                         double exit_cap, bool continues) {
  // The items this move is charged with: its blend arc in (less what of it ran the move before),
  // and its own segment, or, when a blend consumed what was left of it, the part of the next
  // blend arc that runs that rest (LinuxCNC lists such a move with no time at all).
  Charge charge;
  charge.first = pending_arc_in_ ? *pending_arc_in_ : static_cast<std::uint32_t>(items_.size());
  charge.count = pending_arc_in_ ? 1 : 0;
  const double begin = pending_arc_in_ ? arc_in_skip_ : 0;
  double end = pending_arc_in_ ? items_[*pending_arc_in_].length : 0;
  if (!consumed) {
    end += items_[push(*pending_, exit_cap)].length;
    ++charge.count;
  }
  pending_arc_in_.reset();
  arc_in_skip_ = 0;
  if (blend) {
    pending_arc_in_ = push(*blend, kUnlimited);
    if (consumed) {
      end += consumed_length;
      arc_in_skip_ = consumed_length;
      ++charge.count;
    }
  }
  double total = 0;
  for (std::uint32_t i = 0; i < charge.count; ++i)
    total += items_[charge.first + i].length;
  double members = 0;
  for (const Member& m : pending_members_)
    members += m.length;
  // Each line's share, in proportion to its length, of the stretch [begin, end].
  auto fraction = [](double at, double of) {
    return of > 0 ? static_cast<float>(std::clamp(at / of, 0.0, 1.0)) : 0.0f;
  };
  double done = 0;
  for (const Member& m : pending_members_) {
    const bool last = &m == &pending_members_.back();
    const double from = members > 0 ? done / members : 0;
    done += m.length;
    const double to = members > 0 && !last ? done / members : 1;
    const double from_mm = begin + (end - begin) * from, to_mm = begin + (end - begin) * to;
    if (last && continues) { // its end is in the next segment
      open_charge_ = OpenCharge{m.command, charge.first, from_mm};
      continue;
    }
    if (open_charge_ && open_charge_->command == m.command) { // its middle was in the last one
      Charge whole;
      whole.first = open_charge_->first;
      whole.count = static_cast<std::uint16_t>(charge.first + charge.count - whole.first);
      double before = 0; // from the start of the first item to this segment's first
      for (std::uint32_t i = whole.first; i < charge.first; ++i)
        before += items_[i].length;
      whole.begin = fraction(open_charge_->begin_mm, before + total);
      whole.end = fraction(before + to_mm, before + total);
      open_charge_.reset();
      sink_(m.command, whole);
      continue;
    }
    charge.begin = fraction(from_mm, total);
    charge.end = fraction(to_mm, total);
    sink_(m.command, charge);
  }
  pending_.reset();
}

std::uint32_t PathBuilder::push(const Segment& s, double exit_cap) {
  SpeedPlanItem item{std::max(0.0, s.length - s.overlap), s.target_vel(), s.tangential_accel(), 0,
                     0};
  item.linear_ramp = s.term == Term::Tangent && !s.traverse;
  if (flowing_ && !items_.empty()) {
    SpeedPlanItem& before = items_.back();
    before.junction_after = std::min({exit_cap_, before.vmax, item.vmax});
  }
  items_.push_back(item);
  flowing_ = exit_cap > 0;
  exit_cap_ = exit_cap;
  return static_cast<std::uint32_t>(items_.size() - 1);
}

void PathBuilder::apply_state(Segment& s, const CanonCommand& c) {
  const ModalState& st = c.state;
  if (st.path_mode == PathMode::Continuous)
    s.tolerance = startup_tolerance_ ? kStartupTolerance_mm : st.path_tolerance;
  if (machine_.exact_stop_every_block || st.path_mode == PathMode::ExactStop)
    s.term = Term::Stop;
  else
    s.term = st.path_mode == PathMode::ExactPath ? Term::Exact : Term::Parabolic;
  s.traverse = c.kind == CanonKind::Traverse;
  s.rotary = moves_rotary(c);
  if (!s.traverse && atspeed_next_feed_) {
    s.atspeed = true;
    atspeed_next_feed_ = false;
  }
}

// A straight move as emccanon sends it: the feed, capped so that no axis exceeds its limit along
// the line, and the acceleration of the slowest axis along it. `limits`: those of the line
// from start to end, where the caller has them (a line sent as it is: `last` itself).
Segment PathBuilder::line_segment(const CanonCommand& last, const Pose& start, const Pose& end,
                                  const MoveLimits* limits) const {
  auto chord_limits = [&] {
    CanonCommand chord;
    // An arc the naive-CAM detector took in is run as part of a straight move.
    chord.kind = last.kind == CanonKind::Arc ? CanonKind::Feed : last.kind;
    chord.line = last.line;
    chord.start = start;
    chord.end = end;
    chord.state = last.state;
    return move_limits(chord, machine_, scratch_);
  };
  const MoveLimits m = limits ? *limits : chord_limits();
  Segment s;
  s.shape = Shape::Line;
  s.start = xyz(start);
  s.end = xyz(end);
  s.direction = m.dir_in;
  s.length = s.nominal = m.length;
  s.reqvel = m.vmax;
  s.maxvel = std::min(m.vmax_machine, m.length / kCycle_s); // tcClampVelocityByLength
  s.accel = m.accel;
  return s;
}

// An arc as emccanon's ARC_FEED sends it: the speed held to sqrt(0.866 a r) in the plane and to
// the axes' limits, the acceleration of the slower plane axis.
Segment PathBuilder::circle_segment(const CanonCommand& c) const {
  const ArcGeometry g = arc_geometry(c);
  const auto [first, second, normal_axis] = plane_axes(c.plane);
  const Vec3 start = xyz(c.start), end = xyz(c.end);
  const double axial = end[normal_axis] - start[normal_axis];
  Vec3 centre = start; // the centre in the start's plane
  centre[first] = c.centre_first;
  centre[second] = c.centre_second;

  Segment s;
  s.shape = Shape::Circle;
  Circle& k = s.circle;
  k.centre = centre;
  k.normal = axis_vector(normal_axis, g.sweep >= 0 ? 1.0 : -1.0);
  k.r_tan = start - centre;
  k.r_perp = k.normal.cross(k.r_tan);
  k.radius = k.r_tan.norm();
  const Vec3 end_in_plane = end - centre - axis_vector(normal_axis, axial);
  k.spiral = end_in_plane.norm() - k.radius;
  k.angle = std::abs(g.sweep);
  k.r_helix = axis_vector(normal_axis, axial);
  s.start = start;
  s.end = end;
  s.length = s.nominal = g.length;

  const auto& axes = machine_.axes;
  const double v_axes = std::min(axes[first].max_feed_mm_s, axes[second].max_feed_mm_s);
  const double a_axes = std::min(axes[first].accel_mm_s2, axes[second].accel_mm_s2);
  const double end_radius = k.radius + k.spiral;
  const double dr = k.angle > 0 ? k.spiral / k.angle : 0;
  const double min_radius = std::min(k.radius, end_radius);
  const double effective_radius = std::sqrt(dr * dr + min_radius * min_radius);
  const double v_planar =
      std::min(std::sqrt(kNormalAccelRatio * a_axes * effective_radius), v_axes);
  const double spiral_length = std::hypot(min_radius * k.angle, k.spiral);
  const double total = std::hypot(spiral_length, axial);
  // Time and "acceleration time" the chord needs on the axes (getStraightVelocity/Acceleration).
  double t_motion = 0, tt_motion = 0;
  for (int i = 0; i < 3; ++i) {
    const double d = std::abs(end[i] - start[i]);
    if (d < 1e-9) continue;
    t_motion = std::max(t_motion, d / axes[i].max_feed_mm_s);
    tt_motion = std::max(tt_motion, d / axes[i].accel_mm_s2);
  }
  const double t_max = std::max(t_motion, spiral_length / v_planar);
  const double tt_max = std::max(tt_motion, spiral_length / a_axes);
  const double v_max = t_max > 0 ? total / t_max : v_axes;
  s.accel = tt_max > 0 ? total / tt_max : a_axes;
  // The programmed feed, as move_limits reads it (G93, G94, G95).
  const MoveLimits m = move_limits(c, machine_, scratch_);
  const double programmed = m.vmax < m.vmax_machine ? m.vmax : kUnlimited;
  s.reqvel = std::min(programmed, v_max);
  s.maxvel = std::min(v_max, s.length / kCycle_s);
  return s;
}

} // namespace ncjoule::kinematics_detail::linuxcnc
