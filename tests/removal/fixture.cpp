#include "fixture.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <sstream>

namespace ncjoule::test {

ProgramBuilder& ProgramBuilder::tool(int number) {
  state_.tool = number;
  return *this;
}

ProgramBuilder& ProgramBuilder::feed_rate(double mm_per_min) {
  state_.feed = mm_per_min;
  return *this;
}

CanonCommand& ProgramBuilder::add(CanonKind kind, double x, double y, double z) {
  CanonCommand c;
  c.kind = kind;
  c.line = int(commands_.size());
  c.call_line = c.line;
  c.start = at_;
  c.end = at_;
  c.end.x = x, c.end.y = y, c.end.z = z;
  c.state = state_;
  at_ = c.end;
  commands_.push_back(c);
  return commands_.back();
}

ProgramBuilder& ProgramBuilder::rapid(double x, double y, double z) {
  add(CanonKind::Traverse, x, y, z);
  return *this;
}

ProgramBuilder& ProgramBuilder::feed(double x, double y, double z) {
  add(CanonKind::Feed, x, y, z);
  return *this;
}

ProgramBuilder& ProgramBuilder::arc(double x, double y, double z, double cx, double cy,
                                    int rotation) {
  CanonCommand& c = add(CanonKind::Arc, x, y, z);
  c.centre_first = cx, c.centre_second = cy, c.rotation = rotation;
  return *this;
}

ProgramBuilder& ProgramBuilder::arc_in(Plane plane, double x, double y, double z, double c1,
                                       double c2, int rotation) {
  CanonCommand& c = add(CanonKind::Arc, x, y, z);
  c.plane = c.state.plane = plane;
  c.centre_first = c1, c.centre_second = c2, c.rotation = rotation;
  return *this;
}

Timeline constant_speed_timeline(const std::vector<CanonCommand>& commands, double max_step_mm,
                                 double rapid_mm_s) {
  Timeline tl;
  double t = 0;
  for (std::size_t k = 0; k < commands.size(); ++k) {
    const CanonCommand& c = commands[k];
    TimedCommand tc;
    tc.command = k;
    tc.line = c.line;
    tc.kind = c.kind;
    tc.start_s = t;
    const bool move =
        c.kind == CanonKind::Traverse || c.kind == CanonKind::Feed || c.kind == CanonKind::Arc;
    if (move) {
      const double length = move_length(c);
      const double speed = c.kind == CanonKind::Traverse ? rapid_mm_s : c.state.feed / 60.0;
      tc.length_mm = length;
      tc.duration_s = length / speed;
      tc.entry_speed_mm_s = tc.exit_speed_mm_s = tc.peak_speed_mm_s = speed;
      const int n = max_step_mm > 0 ? std::max(1, int(std::ceil(length / max_step_mm - 1e-9))) : 1;
      for (int i = 0; i <= n; ++i) {
        MotionSample s;
        s.u = double(i) / n;
        s.t_s = t + tc.duration_s * s.u;
        s.position = point_on_move(c, s.u);
        s.speed_mm_s = speed;
        tc.samples.push_back(s);
      }
    }
    t += tc.duration_s;
    tl.commands.push_back(std::move(tc));
  }
  tl.total_s = t;
  return tl;
}

Tool flat_end_mill(int number, double diameter) {
  Tool t;
  t.number = number;
  t.shape = ToolShape::FlatEndMill;
  t.diameter_mm = diameter;
  return t;
}

Tool ball_end_mill(int number, double diameter) {
  Tool t = flat_end_mill(number, diameter);
  t.shape = ToolShape::BallEndMill;
  t.corner_radius_mm = diameter / 2;
  return t;
}

Tool drill(int number, double diameter, double point_angle_deg) {
  Tool t = flat_end_mill(number, diameter);
  t.shape = ToolShape::Drill;
  t.tip_angle_deg = point_angle_deg;
  return t;
}

TriangleMesh box_mesh(const Box3& b) {
  const double x[2] = {b.xmin, b.xmax}, y[2] = {b.ymin, b.ymax}, z[2] = {b.zmin, b.zmax};
  auto corner = [&](int i, int j, int k, double* v) { v[0] = x[i], v[1] = y[j], v[2] = z[k]; };
  // Each face as two triangles over its four corners, given as (i, j, k) bits.
  const int faces[6][4][3] = {
      {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
      {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};
  TriangleMesh mesh;
  for (const auto& f : faces) {
    Triangle t1, t2;
    corner(f[0][0], f[0][1], f[0][2], t1.v[0]);
    corner(f[1][0], f[1][1], f[1][2], t1.v[1]);
    corner(f[2][0], f[2][1], f[2][2], t1.v[2]);
    corner(f[0][0], f[0][1], f[0][2], t2.v[0]);
    corner(f[2][0], f[2][1], f[2][2], t2.v[1]);
    corner(f[3][0], f[3][1], f[3][2], t2.v[2]);
    mesh.triangles.push_back(t1);
    mesh.triangles.push_back(t2);
  }
  return mesh;
}

std::string ascii_stl(const TriangleMesh& mesh) {
  std::ostringstream out;
  out.precision(17);
  out << "solid stock\n";
  for (const Triangle& t : mesh.triangles) {
    out << "  facet normal 0 0 0\n    outer loop\n";
    for (const auto& v : t.v)
      out << "      vertex " << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid stock\n";
  return out.str();
}

std::string binary_stl(const TriangleMesh& mesh) {
  std::string out(80, ' ');
  out.replace(0, 11, "solid stock"); // some exporters do this; the reader must cope
  auto put_u32 = [&](std::uint32_t v) {
    for (int k = 0; k < 4; ++k)
      out += char((v >> (8 * k)) & 0xff);
  };
  auto put_f32 = [&](float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    put_u32(u);
  };
  put_u32(std::uint32_t(mesh.triangles.size()));
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k)
      put_f32(0);
    for (const auto& v : t.v)
      for (int k = 0; k < 3; ++k)
        put_f32(float(v[k]));
    out += '\0', out += '\0';
  }
  return out;
}

std::string temp_dir() {
  std::random_device rd;
  const auto dir =
      std::filesystem::temp_directory_path() / ("ncjoule_removal_test_" + std::to_string(rd()));
  std::filesystem::create_directories(dir);
  return dir.string();
}

} // namespace ncjoule::test

#include <cstdio>
#include <cstdlib>

namespace ncjoule::test {
void report(const std::string& what, double value) {
  if (std::getenv("NCJOULE_TEST_VERBOSE")) std::fprintf(stderr, "%s: %.6g\n", what.c_str(), value);
}
} // namespace ncjoule::test
