// Every sample program under samples/programs, estimated with both removal engines at the same
// grid through estimate_program: the removed volumes agree within 0.5%. A sample's stock is the
// --stock text in the file beside it with the extension .stock (the default box otherwise).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"

using namespace ncjoule;
namespace fs = std::filesystem;

namespace {

// The same grid for both engines, coarse enough for the voxel reference to run in a test.
constexpr double kGridMm = 0.25;
constexpr std::size_t kMaxColumns = 250'000;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string trimmed(std::string s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
    s.pop_back();
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
    s.erase(s.begin());
  return s;
}

} // namespace

TEST_CASE("dexel and voxel agree within 0.5% on every sample program") {
  const fs::path samples = fs::path(NCJOULE_SOURCE_DIR) / "samples" / "programs";
  std::vector<fs::path> programs;
  for (const auto& entry : fs::directory_iterator(samples))
    if (entry.path().extension() == ".ngc" || entry.path().extension() == ".nc")
      programs.push_back(entry.path());
  std::sort(programs.begin(), programs.end());
  REQUIRE(!programs.empty());
  const MachineProfile machine =
      load_profile((fs::path(NCJOULE_SOURCE_DIR) / "samples/machines/generic-3axis.toml").string());

  for (const fs::path& program : programs) {
    CAPTURE(program.filename().string());
    const SourceFile source = make_source(program.string(), read_text(program));
    EstimateOptions options;
    fs::path stock_file = program;
    stock_file.replace_extension(".stock");
    if (fs::exists(stock_file)) {
      std::vector<Diagnostic> problems;
      options.stock =
          parse_stock_spec(trimmed(read_text(stock_file)), &problems, {stock_file.string(), 1, 1});
      const std::string problem = problems.empty() ? "" : format_diagnostic(problems[0]);
      REQUIRE_MESSAGE(options.stock, problem);
      if (options.stock->kind == StockSpec::Kind::Stl)
        options.stock->stl_path = (samples / options.stock->stl_path).string();
    }
    options.removal.grid_mm = kGridMm;
    options.removal.max_columns = kMaxColumns;
    options.removal.engine = EngineKind::Dexel;
    const Estimate dexel = estimate_program(source, machine, options);
    options.removal.engine = EngineKind::Voxel;
    options.removal.max_voxels = kMaxColumns * 400;
    const Estimate voxel = estimate_program(source, machine, options);
    REQUIRE_FALSE(dexel.failed);
    REQUIRE_FALSE(voxel.failed);
    REQUIRE(dexel.removal);
    REQUIRE(voxel.removal);
    // The same columns, or the comparison is not at the same grid.
    CHECK(dexel.removal->grid.dx == voxel.removal->grid.dx);
    CHECK(dexel.removal->grid.dy == voxel.removal->grid.dy);
    const double d = dexel.removal->removed_mm3, v = voxel.removal->removed_mm3;
    REQUIRE(d > 0);
    const double difference = std::abs(v - d) / d;
    MESSAGE(program.filename().string(), ": dexel ", d, " mm^3, voxel ", v, " mm^3, ",
            100 * difference, " %");
    CHECK(difference < 5e-3);
  }
}
