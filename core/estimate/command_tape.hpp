// Internal: a program's canonical commands as the estimate's first pass got them from the
// interpreter, held compactly for its second pass, which replays them instead of reading and
// interpreting the text again.
//
// Each command is written as what differs from the one before it: most are moves, whose kind,
// line and the coordinates that changed are all that is new (about 20 bytes, where a
// CanonCommand takes 240). A replayed command is the recorded one bit for bit, every field (a
// -0.0 stays -0.0), so the second pass gives the numbers interpreting again would.
//
// The tape holds at most the bytes it is given; a program that needs more (loops and calls that
// run far more commands than it has lines) stops recording, and the second pass interprets the
// text again as before.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "ncjoule/gcode.hpp"

namespace ncjoule::estimate_detail {

class CommandTape {
public:
  explicit CommandTape(std::size_t max_bytes) : max_bytes_(max_bytes) {}

  // Records the next command; once over max_bytes, drops everything and records no more.
  void record(const CanonCommand& c);
  // Every command given to record() is on the tape.
  bool complete() const { return !overflowed_; }
  std::size_t commands() const { return commands_; }
  std::size_t bytes() const { return bytes_; }

  // Gives the recorded commands to `sink` in order. `release`: frees the tape's memory as it
  // goes (the last replay); else the tape can be replayed again. Needs complete().
  void replay(const std::function<void(const CanonCommand&)>& sink, bool release = true);

private:
  // Memory in pieces of this size: the tape grows without copying and is freed as it is read.
  static constexpr std::size_t kChunkBytes = std::size_t(1) << 20;
  struct Chunk {
    explicit Chunk(std::size_t bytes) : data(new unsigned char[bytes]), capacity(bytes) {}
    std::unique_ptr<unsigned char[]> data;
    std::size_t capacity, used = 0;
  };
  // Room for `n` bytes at the end of the tape (a new chunk where the last has too little).
  unsigned char* room(std::size_t n);

  std::size_t max_bytes_;
  std::vector<Chunk> chunks_;
  std::size_t bytes_ = 0, commands_ = 0;
  bool overflowed_ = false;
  CanonCommand last_; // what the next record() is written against
};

} // namespace ncjoule::estimate_detail
