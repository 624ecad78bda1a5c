// Reading STL files, binary and ASCII.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "ncjoule/removal.hpp"
#include "ncjoule/text_file.hpp"

namespace ncjoule {
namespace {

constexpr std::size_t kBinaryHeader = 80;
constexpr std::size_t kBinaryTriangle = 50; // normal, 3 vertices (12 floats), attribute word

float read_float_le(const char* p) {
  unsigned char b[4];
  std::memcpy(b, p, 4);
  const std::uint32_t u = std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 |
                          std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

// A binary STL's size is fixed by its triangle count; ASCII files begin with "solid", but some
// binary exporters write "solid" into the header too, so the size decides first.
bool looks_binary(std::string_view bytes) {
  if (bytes.size() < kBinaryHeader + 4) return false;
  const unsigned char* p = reinterpret_cast<const unsigned char*>(bytes.data() + kBinaryHeader);
  const std::uint64_t n = std::uint64_t(p[0]) | std::uint64_t(p[1]) << 8 |
                          std::uint64_t(p[2]) << 16 | std::uint64_t(p[3]) << 24;
  return bytes.size() == kBinaryHeader + 4 + n * kBinaryTriangle;
}

std::optional<TriangleMesh> parse_binary(std::string_view bytes, std::string& error) {
  TriangleMesh mesh;
  const std::size_t n = (bytes.size() - kBinaryHeader - 4) / kBinaryTriangle;
  mesh.triangles.reserve(n);
  for (std::size_t t = 0; t < n; ++t) {
    const char* p = bytes.data() + kBinaryHeader + 4 + t * kBinaryTriangle + 12; // skip normal
    Triangle tri;
    for (int v = 0; v < 3; ++v)
      for (int k = 0; k < 3; ++k)
        tri.v[v][k] = read_float_le(p + 4 * (3 * v + k));
    mesh.triangles.push_back(tri);
  }
  if (mesh.triangles.empty()) {
    error = "binary STL with no triangles";
    return std::nullopt;
  }
  return mesh;
}

// `line` is set to where an error was found (1-based).
std::optional<TriangleMesh> parse_ascii(std::string_view bytes, std::string& error, int& line) {
  TriangleMesh mesh;
  std::istringstream in{std::string(bytes)};
  auto fail = [&](std::string why) -> std::optional<TriangleMesh> {
    const std::streamoff at = in.tellg();
    const std::size_t end = at < 0 ? bytes.size() : std::size_t(at);
    line = 1 + int(std::count(bytes.begin(), bytes.begin() + std::min(end, bytes.size()), '\n'));
    error = std::move(why);
    return std::nullopt;
  };
  std::string word;
  Triangle tri;
  int vertex = 0;
  std::size_t line_words = 0;
  while (in >> word) {
    ++line_words;
    for (char& ch : word)
      ch = char(std::tolower(static_cast<unsigned char>(ch)));
    if (word == "vertex") {
      if (vertex >= 3) return fail("ASCII STL facet with more than three vertices");
      for (int k = 0; k < 3; ++k) {
        std::string number;
        if (!(in >> number)) return fail("ASCII STL ends inside a vertex");
        double value = 0;
        const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
        if (ec != std::errc() || end != number.data() + number.size() || !std::isfinite(value))
          return fail("ASCII STL vertex coordinate '" + number + "' is not a finite number");
        tri.v[vertex][k] = value;
      }
      ++vertex;
    } else if (word == "endfacet") {
      if (vertex != 3) return fail("ASCII STL facet without three vertices");
      mesh.triangles.push_back(tri);
      vertex = 0;
    }
  }
  if (mesh.triangles.empty()) {
    error = line_words ? "no facets found (neither an ASCII nor a binary STL)" : "empty file";
    return std::nullopt;
  }
  return mesh;
}

} // namespace

std::optional<TriangleMesh> parse_stl(std::string_view bytes, const std::string& path,
                                      std::vector<Diagnostic>& diagnostics) {
  std::string error;
  int line = 0;
  auto mesh = looks_binary(bytes) ? parse_binary(bytes, error) : parse_ascii(bytes, error, line);
  if (!mesh) diagnostics.push_back({Severity::Error, path, line, 0, error});
  return mesh;
}

std::optional<TriangleMesh> read_stl(const std::string& path,
                                     std::vector<Diagnostic>& diagnostics) {
  // A part's STL can be tens of megabytes; a quarter of a gigabyte is 5 million triangles.
  constexpr std::size_t kMaxStlBytes = std::size_t(256) << 20;
  const std::optional<std::string> bytes =
      read_text_file(path, "an STL file", diagnostics, kMaxStlBytes);
  if (!bytes) return std::nullopt;
  return parse_stl(*bytes, path, diagnostics);
}

} // namespace ncjoule
