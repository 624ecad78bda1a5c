#include "command_tape.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

namespace ncjoule::estimate_detail {
namespace {

// Every field of CanonCommand and ModalState is written below: a field added to either must be
// added here too, or replayed commands would lose it. These sizes (GCC or clang with libstdc++
// on x86-64) fail the build when the structs change, as a reminder.
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(ModalState) == 56, "a field added to ModalState: write it on the tape");
static_assert(sizeof(CanonCommand) == 240, "a field added to CanonCommand: write it on the tape");
#endif

// A record starts with 32 bits: the command's kind in the top byte, then these flags.
enum Flag : std::uint32_t {
  kLineNext = 1u << 0,   // line is the last one's + 1 (else, with kLineSame unset, written)
  kLineSame = 1u << 1,   // line is the last one's
  kCallIsLine = 1u << 2, // call_line == line (else written)
  kStartKnown = 1u << 3, // the value of start_known
  kAxes = 1u << 4,       // machine_axes written (else the last one's)
  kArc = 1u << 5,        // centre_first, centre_second, rotation and plane written
  kValue = 1u << 6,      // value written
  kText = 1u << 7,       // text written (its length, then its bytes)
  kState = 1u << 8,      // state written
  // Bits 9-14: the axes (x y z a b c) of start that differ from the last command's end, each
  // written; bits 15-20: the same for end.
  kStartAxesShift = 9,
  kEndAxesShift = 15,
};
constexpr int kKindShift = 24;
// The largest record without its text: head, line, call line, 12 coordinates, axes, arc,
// value, the text's length and the state.
constexpr std::size_t kMaxFixedBytes = 4 + 4 + 4 + 12 * 8 + 1 + (8 + 8 + 4 + 1) + 8 + 4 + 64;

bool same(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

double& axis(Pose& p, int i) {
  double* axes[] = {&p.x, &p.y, &p.z, &p.a, &p.b, &p.c};
  return *axes[i];
}
double axis(const Pose& p, int i) {
  const double axes[] = {p.x, p.y, p.z, p.a, p.b, p.c};
  return axes[i];
}

// Bit i set where axis i of `p` differs from that of `reference`, bit for bit.
std::uint32_t changed_axes(const Pose& p, const Pose& reference) {
  std::uint32_t mask = 0;
  for (int i = 0; i < 6; ++i)
    if (!same(axis(p, i), axis(reference, i))) mask |= 1u << i;
  return mask;
}

bool same_state(const ModalState& a, const ModalState& b) {
  return a.feed_mode == b.feed_mode && same(a.feed, b.feed) && same(a.spindle_rpm, b.spindle_rpm) &&
         a.spindle == b.spindle && a.mist == b.mist && a.flood == b.flood && a.tool == b.tool &&
         a.inch == b.inch && a.path_mode == b.path_mode &&
         same(a.path_tolerance, b.path_tolerance) && a.plane == b.plane;
}

// Writes and reads plain values at a moving pointer.
template <class T> void put(unsigned char*& p, T v) {
  std::memcpy(p, &v, sizeof v);
  p += sizeof v;
}
template <class T> T take(const unsigned char*& p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  p += sizeof v;
  return v;
}

void put_state(unsigned char*& p, const ModalState& s) {
  put(p, s.feed_mode);
  put(p, s.feed);
  put(p, s.spindle_rpm);
  put(p, s.spindle);
  put(p, s.mist);
  put(p, s.flood);
  put(p, s.tool);
  put(p, s.inch);
  put(p, s.path_mode);
  put(p, s.path_tolerance);
  put(p, s.plane);
}

void take_state(const unsigned char*& p, ModalState& s) {
  s.feed_mode = take<FeedMode>(p);
  s.feed = take<double>(p);
  s.spindle_rpm = take<double>(p);
  s.spindle = take<SpindleDir>(p);
  s.mist = take<bool>(p);
  s.flood = take<bool>(p);
  s.tool = take<int>(p);
  s.inch = take<bool>(p);
  s.path_mode = take<PathMode>(p);
  s.path_tolerance = take<double>(p);
  s.plane = take<Plane>(p);
}

} // namespace

unsigned char* CommandTape::room(std::size_t n) {
  if (chunks_.empty() || chunks_.back().capacity - chunks_.back().used < n) {
    // A record longer than a chunk (a comment of a megabyte) gets a chunk of its own size.
    chunks_.emplace_back(std::max(n, kChunkBytes));
  }
  Chunk& chunk = chunks_.back();
  return chunk.data.get() + chunk.used;
}

void CommandTape::record(const CanonCommand& c) {
  if (overflowed_) return;
  std::uint32_t flags = std::uint32_t(c.kind) << kKindShift;
  if (c.line == last_.line + 1)
    flags |= kLineNext;
  else if (c.line == last_.line)
    flags |= kLineSame;
  if (c.call_line == c.line) flags |= kCallIsLine;
  if (c.start_known) flags |= kStartKnown;
  if (c.machine_axes != last_.machine_axes) flags |= kAxes;
  if (!same(c.centre_first, last_.centre_first) || !same(c.centre_second, last_.centre_second) ||
      c.rotation != last_.rotation || c.plane != last_.plane)
    flags |= kArc;
  if (!same(c.value, last_.value)) flags |= kValue;
  if (c.text != last_.text) flags |= kText;
  if (!same_state(c.state, last_.state)) flags |= kState;
  const std::uint32_t start_axes = changed_axes(c.start, last_.end);
  const std::uint32_t end_axes = changed_axes(c.end, last_.end);
  flags |= start_axes << kStartAxesShift | end_axes << kEndAxesShift;

  const std::size_t text_bytes = flags & kText ? c.text.size() : 0;
  const std::size_t most = kMaxFixedBytes + text_bytes;
  if (bytes_ + most > max_bytes_) {
    overflowed_ = true;
    chunks_.clear();
    chunks_.shrink_to_fit();
    bytes_ = 0;
    return;
  }
  unsigned char* const begin = room(most);
  unsigned char* p = begin;
  put(p, flags);
  if (!(flags & (kLineNext | kLineSame))) put(p, std::int32_t(c.line));
  if (!(flags & kCallIsLine)) put(p, std::int32_t(c.call_line));
  for (int i = 0; i < 6; ++i)
    if (start_axes & (1u << i)) put(p, axis(c.start, i));
  for (int i = 0; i < 6; ++i)
    if (end_axes & (1u << i)) put(p, axis(c.end, i));
  if (flags & kAxes) put(p, c.machine_axes);
  if (flags & kArc) {
    put(p, c.centre_first);
    put(p, c.centre_second);
    put(p, std::int32_t(c.rotation));
    put(p, c.plane);
  }
  if (flags & kValue) put(p, c.value);
  if (flags & kState) put_state(p, c.state);
  if (flags & kText) {
    put(p, std::uint32_t(c.text.size()));
    std::memcpy(p, c.text.data(), c.text.size());
    p += c.text.size();
  }
  const auto written = std::size_t(p - begin);
  chunks_.back().used += written;
  bytes_ += written;
  ++commands_;
  last_ = c;
}

void CommandTape::replay(const std::function<void(const CanonCommand&)>& sink, bool release) {
  CanonCommand c; // the last command, which the next record changes
  for (Chunk& chunk : chunks_) {
    const unsigned char* p = chunk.data.get();
    const unsigned char* const end = p + chunk.used;
    while (p < end) {
      const auto flags = take<std::uint32_t>(p);
      c.kind = CanonKind(flags >> kKindShift);
      if (flags & kLineNext)
        ++c.line;
      else if (!(flags & kLineSame))
        c.line = take<std::int32_t>(p);
      c.call_line = flags & kCallIsLine ? c.line : take<std::int32_t>(p);
      c.start_known = flags & kStartKnown;
      c.start = c.end;
      for (int i = 0; i < 6; ++i)
        if (flags & (1u << (kStartAxesShift + i))) axis(c.start, i) = take<double>(p);
      for (int i = 0; i < 6; ++i)
        if (flags & (1u << (kEndAxesShift + i))) axis(c.end, i) = take<double>(p);
      if (flags & kAxes) c.machine_axes = take<std::uint8_t>(p);
      if (flags & kArc) {
        c.centre_first = take<double>(p);
        c.centre_second = take<double>(p);
        c.rotation = take<std::int32_t>(p);
        c.plane = take<Plane>(p);
      }
      if (flags & kValue) c.value = take<double>(p);
      if (flags & kState) take_state(p, c.state);
      if (flags & kText) {
        const auto size = take<std::uint32_t>(p);
        c.text.assign(reinterpret_cast<const char*>(p), size);
        p += size;
      }
      sink(c);
    }
    if (release) chunk.data.reset();
  }
  if (!release) return;
  chunks_.clear();
  bytes_ = 0;
}

} // namespace ncjoule::estimate_detail
