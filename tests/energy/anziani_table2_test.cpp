// Anziani (2025) Table 2: nine straight 155 mm cuts on the Zhou/Anziani machine (Table 1
// constants). MRR comes from the exact cross-section depth * width for now; the test named
// "...with exact MRR" is the one to switch to the removal engine once it lands.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "anziani_table2.hpp"
#include "ncjoule/energy.hpp"
#include "program_builder.hpp"

using namespace ncjoule;
using ncjoule::test::kCutLengthMm;
using ncjoule::test::kTable2;
using ncjoule::test::Table2Row;

namespace {

PowerConstants anziani_table1() {
  PowerConstants k;
  k.model = PowerModel::Zhou;
  k.zhou = {0.78, 0.00017, 8.06e-7, 1.13, 5.39e-6, 1.82, 0.15, 779};
  return k;
}

struct CutPrediction {
  double mrr, power_kw, sec;
};

// One cut of the table: spindle on, then a straight feed along X through the material with a
// constant cross-section (exact MRR = depth * width * feed).
CutPrediction predict_cut_with_exact_mrr(const Table2Row& row, const PowerConstants& k) {
  ncjoule::test::ProgramBuilder b;
  b.sample_dt_s = 0.1;
  b.spindle(row.rpm);
  b.feed({kCutLengthMm, 0, 0}, row.feed_mm_min / 60.0, row.depth_mm * row.width_mm);
  const EnergyResult r = estimate_energy(b.commands, b.timeline, &b.removal, k);
  const CommandEnergy& cut = r.commands.back();
  return {cut.removed_mm3 / cut.duration_s, cut.mean_power_w / 1000.0, cut.sec_j_mm3};
}

} // namespace

TEST_CASE("Anziani Table 2 with exact MRR: power within 0.02 kW, SEC = Zhou's pointwise SEC") {
  const PowerConstants k = anziani_table1();
  double sum_power_err_thesis = 0, sum_power_err_expected = 0, sum_sec_err_expected = 0;
  double sum_sec_err_model = 0;
  std::string table = "test   MRR(pred/exp)   P kW (pred / thesis model / expected)   "
                      "SEC J/mm^3 (pred / Zhou P-formula / Zhou SEC-model / expected)\n";
  for (const Table2Row& row : kTable2) {
    CAPTURE(row.test);
    const CutPrediction p = predict_cut_with_exact_mrr(row, k);
    const double formula_power_kw = zhou_power_kw(k.zhou, row.rpm, row.expected_mrr);
    const double formula_sec = 1000.0 * formula_power_kw / row.expected_mrr;
    const double sec_model = zhou_sec_model_j_mm3(k.zhou, row.rpm, row.expected_mrr);
    CHECK(p.mrr == doctest::Approx(row.expected_mrr).epsilon(1e-9));
    CHECK(std::abs(p.power_kw - row.thesis_model_power_kw) <= 0.02);
    // Energy over removed volume reproduces the formula's pointwise SEC (no per-step bias).
    CHECK(p.sec == doctest::Approx(formula_sec).epsilon(1e-9));
    // Zhou's separate SEC model was fitted to the same data; the two agree within 5%.
    CHECK(std::abs(p.sec - sec_model) / sec_model < 0.05);
    sum_power_err_thesis += std::abs(p.power_kw - row.thesis_model_power_kw);
    sum_power_err_expected += std::abs(p.power_kw - row.expected_power_kw);
    sum_sec_err_expected += std::abs(p.sec - row.expected_sec) / row.expected_sec;
    sum_sec_err_model += std::abs(p.sec - sec_model) / sec_model;
    char line[256];
    std::snprintf(line, sizeof line,
                  "%4d   %6.2f/%6.2f    %.3f / %.2f / %.2f                        "
                  "%7.2f / %7.2f / %7.2f / %7.2f\n",
                  row.test, p.mrr, row.expected_mrr, p.power_kw, row.thesis_model_power_kw,
                  row.expected_power_kw, p.sec, formula_sec, sec_model, row.expected_sec);
    table += line;
  }
  const double n = std::size(kTable2);
  char summary[320];
  std::snprintf(summary, sizeof summary,
                "mean |P - thesis model P| = %.4f kW; mean |P - expected P| = %.4f kW; "
                "mean |SEC - expected SEC| = %.2f%%; mean |SEC - Zhou SEC model| = %.2f%%",
                sum_power_err_thesis / n, sum_power_err_expected / n,
                100 * sum_sec_err_expected / n, 100 * sum_sec_err_model / n);
  MESSAGE(table);
  MESSAGE(summary);
  CHECK(sum_power_err_thesis / n < 0.02);
}
