// Measured against predicted, per program, operation and stretch of lines, over the usable runs:
// the tables `ncjoule check-log` prints and the fit's targets are read from.
#include <algorithm>
#include <cmath>
#include <map>

#include "ncjoule/calibrate_timing.hpp"

namespace ncjoule {
namespace {

MeasuredRange range_of(std::vector<double> v) {
  MeasuredRange r;
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return r;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  r.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  r.min = v.front();
  r.max = v.back();
  r.runs = n;
  return r;
}

double median_of(std::vector<double> v) {
  return range_of(std::move(v)).median;
}

std::string shortened(std::string_view text) {
  while (!text.empty() && (text.back() == '\r' || text.back() == ' '))
    text.remove_suffix(1);
  return text.size() > 48 ? std::string(text.substr(0, 45)) + "..." : std::string(text);
}

} // namespace

std::vector<ProgramCheck> check_programs(const LogEvidence& evidence,
                                         const std::vector<LineTimes>& times,
                                         std::size_t worst_blocks) {
  std::vector<ProgramCheck> checks;
  for (std::size_t p = 0; p < evidence.programs.size(); ++p) {
    ProgramCheck c;
    c.program = p;
    const LoggedProgram& program = evidence.programs[p];
    const LineTimes& t = times[p];
    // Operations start at their lines (the first at the program's start).
    std::vector<int> starts;
    for (const OperationSummary& op : program.estimate.operations) {
      OperationCheck oc;
      oc.name = op.name;
      oc.tool = op.tool;
      oc.line = op.line >= 0 ? op.line + 1 : 1;
      c.operations.push_back(oc);
      starts.push_back(oc.line);
    }
    auto op_of = [&](int line) {
      std::size_t k = 0;
      while (k + 1 < starts.size() && starts[k + 1] <= line)
        ++k;
      return k;
    };
    std::vector<double> totals, predicted_totals;
    std::vector<std::vector<double>> op_measured(starts.size()), op_predicted(starts.size());
    std::map<std::pair<int, int>, std::pair<std::vector<double>, std::vector<double>>> blocks;
    for (const LoggedRun& r : evidence.program_runs) {
      if (r.program != p) continue;
      ++c.runs;
      if (!r.usable) continue;
      ++c.usable_runs;
      totals.push_back(r.measured_s);
      double predicted = 0;
      std::vector<double> per_op(starts.size(), 0.0);
      for (const LineGroup& g : r.groups) {
        const double rapid = evidence.rapid_at(r, g.start_s);
        const double feed = evidence.feed_at(r, g.start_s);
        const int end = std::min<long long>(g.next, static_cast<long long>(t.a.size()));
        double group_predicted = 0;
        for (int l = g.first; l < end; ++l) {
          const double lt = t.between(l, l + 1, rapid, feed);
          group_predicted += lt;
          if (!starts.empty()) per_op[op_of(l)] += lt;
        }
        predicted += group_predicted;
        auto& b = blocks[{g.first, g.next}];
        b.first.push_back(g.duration_s);
        b.second.push_back(group_predicted);
      }
      predicted_totals.push_back(predicted);
      const auto measured_ops =
          stretch_times(evidence.alignments[r.run], evidence.runs[r.run].end_s, starts);
      for (std::size_t k = 0; k < starts.size(); ++k) {
        op_measured[k].push_back(measured_ops[k]);
        op_predicted[k].push_back(per_op[k]);
      }
    }
    c.measured = range_of(totals);
    c.predicted_s = c.usable_runs ? median_of(predicted_totals) : t.total();
    for (std::size_t k = 0; k < starts.size(); ++k) {
      c.operations[k].measured = range_of(op_measured[k]);
      c.operations[k].predicted_s = c.usable_runs ? median_of(op_predicted[k]) : 0.0;
    }
    if (c.usable_runs == 0) c.operations.clear();
    for (const auto& [range, values] : blocks) {
      if (values.first.size() * 2 < c.usable_runs) continue; // shown this way in few runs
      BlockCheck b;
      b.first = range.first;
      // The last stretch runs to the end of the program.
      b.next = std::min<long long>(range.second,
                                   static_cast<long long>(program.source.lines.size()) + 1);
      b.measured = range_of(values.first);
      b.predicted_s = median_of(values.second);
      if (b.measured.median < 0.5) continue;
      // The line that takes the most of the stretch says what it is (a tool change after a
      // header, an M30 after the lines it hides).
      int telling = b.first;
      for (int l = b.first; l < b.next && l < int(t.a.size()); ++l)
        if (t.between(l, l + 1) > t.between(telling, telling + 1)) telling = l;
      if (telling >= 1 && std::size_t(telling) <= program.source.lines.size())
        b.text = shortened(program.source.line_text(std::size_t(telling) - 1));
      c.worst_blocks.push_back(b);
    }
    std::sort(c.worst_blocks.begin(), c.worst_blocks.end(),
              [](const BlockCheck& x, const BlockCheck& y) {
                return std::abs(x.predicted_s - x.measured.median) >
                       std::abs(y.predicted_s - y.measured.median);
              });
    if (c.worst_blocks.size() > worst_blocks) c.worst_blocks.resize(worst_blocks);
    checks.push_back(std::move(c));
  }
  return checks;
}

} // namespace ncjoule
