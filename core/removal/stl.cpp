// Reading STL files, binary and ASCII.
#include <cctype>
#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>

#include "ncjoule/removal.hpp"

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

std::optional<TriangleMesh> parse_ascii(std::string_view bytes, std::string& error) {
  TriangleMesh mesh;
  std::istringstream in{std::string(bytes)};
  std::string word;
  Triangle tri;
  int vertex = 0;
  std::size_t line_words = 0;
  while (in >> word) {
    ++line_words;
    for (char& ch : word)
      ch = char(std::tolower(static_cast<unsigned char>(ch)));
    if (word == "vertex") {
      if (vertex >= 3) {
        error = "ASCII STL facet with more than three vertices";
        return std::nullopt;
      }
      for (int k = 0; k < 3; ++k) {
        std::string number;
        if (!(in >> number)) {
          error = "ASCII STL ends inside a vertex";
          return std::nullopt;
        }
        double value = 0;
        const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
        if (ec != std::errc() || end != number.data() + number.size()) {
          error = "ASCII STL vertex coordinate '" + number + "' is not a number";
          return std::nullopt;
        }
        tri.v[vertex][k] = value;
      }
      ++vertex;
    } else if (word == "endfacet") {
      if (vertex != 3) {
        error = "ASCII STL facet without three vertices";
        return std::nullopt;
      }
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

std::optional<TriangleMesh> parse_stl(std::string_view bytes, std::string& error) {
  if (looks_binary(bytes)) return parse_binary(bytes, error);
  return parse_ascii(bytes, error);
}

std::optional<TriangleMesh> read_stl(const std::string& path, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = "cannot open STL file '" + path + "'";
    return std::nullopt;
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  auto mesh = parse_stl(buffer.str(), error);
  if (!mesh) error = path + ": " + error;
  return mesh;
}

} // namespace ncjoule
