// Anziani Table 2 (see reference/MODELS.md): nine straight cuts of a 12 mm flat end mill, with
// Zhou et al.'s expected values and the thesis's own "Model Power" column.
#pragma once

namespace ncjoule::test {

struct Table2Row {
  int test;
  double rpm, depth_mm, width_mm, feed_mm_min;
  double expected_mrr, expected_power_kw, expected_sec; // Zhou et al.'s values in the thesis
  double thesis_model_power_kw;                         // the thesis's simulation
};

inline constexpr Table2Row kTable2[] = {
    {1, 500, 3.0, 0.50, 120, 3.0, 0.83, 276.67, 0.86},
    {2, 1300, 6.0, 1.50, 120, 18.0, 1.03, 57.22, 1.04},
    {3, 2100, 9.0, 2.00, 120, 36.0, 1.36, 37.78, 1.29},
    {4, 2100, 6.0, 0.50, 180, 9.0, 1.17, 130.00, 1.16},
    {5, 500, 9.0, 1.50, 180, 40.5, 0.95, 23.46, 0.90},
    {6, 1300, 3.0, 2.00, 180, 18.0, 1.03, 57.22, 1.04},
    {7, 1300, 9.0, 0.50, 240, 18.0, 1.01, 56.11, 1.04},
    {8, 2100, 3.0, 1.50, 240, 18.0, 1.24, 68.89, 1.21},
    {9, 500, 6.0, 2.00, 240, 48.0, 0.96, 20.00, 0.90},
};

inline constexpr double kCutLengthMm = 155.0;

} // namespace ncjoule::test
