// Fit from a time-stamped power log of a known program: first the time offset between log and
// program, then the model's constants over the whole trace with a robust loss.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "fit_engine.hpp"

namespace ncjoule {
namespace {

using PP = PowerParameter;

bool is_zhou_parameter(PP p) {
  return p == PP::ZhouC1 || p == PP::ZhouC2 || p == PP::ZhouC3 || p == PP::ZhouC4;
}

// Typical magnitudes for the solver's scaling when a start value is 0.
double fallback_scale(PP p) {
  switch (p) {
  case PP::ZhouC1:
    return 1;
  case PP::ZhouC2:
    return 1e-4;
  case PP::ZhouC3:
    return 1e-6;
  case PP::ZhouC4:
    return 1;
  case PP::SpindleKB:
    return 0.1;
  case PP::SpindleKC:
    return 1e-5;
  case PP::MoveKBX:
  case PP::MoveKBY:
  case PP::MoveKBZ:
  case PP::CutKBX:
  case PP::CutKBY:
  case PP::CutKBZ:
    return 1;
  default:
    return 100;
  }
}

struct LogProblem {
  std::vector<PP> ids;
  std::optional<fit::PowerLawTerm> power_law; // c3, c4 in Zhou and Combined
};

LogProblem make_layout(PowerModel model) {
  LogProblem layout;
  layout.ids = model_parameters(model);
  auto at = [&](PP p) {
    return static_cast<std::size_t>(std::find(layout.ids.begin(), layout.ids.end(), p) -
                                    layout.ids.begin());
  };
  if (model != PowerModel::Pavanaskar)
    layout.power_law = fit::PowerLawTerm{at(PP::ZhouC3), at(PP::ZhouC4)};
  return layout;
}

// Observations of the log with the program shifted by offset. With `exponent` set, the
// power-law term becomes a linear column at that fixed exponent.
std::vector<fit::Observation> observations(const PowerLog& log,
                                           const std::vector<OperatingSegment>& trace,
                                           PowerModel model, const LogProblem& layout,
                                           double offset_s, std::optional<double> exponent) {
  std::vector<fit::Observation> out(log.t_s.size());
  for (std::size_t i = 0; i < log.t_s.size(); ++i) {
    const OperatingPoint op = operating_point_at(trace, log.t_s[i] - offset_s);
    const PowerFeatures f = power_features(model, op);
    fit::Observation& o = out[i];
    o.y = log.power_w[i];
    o.x.resize(layout.ids.size());
    for (std::size_t j = 0; j < layout.ids.size(); ++j)
      o.x[j] = f.linear[static_cast<std::size_t>(layout.ids[j])];
    if (layout.power_law && f.zhou_mrr_weight_w != 0.0 && f.zhou_rpm > 0) {
      if (exponent) {
        o.x[layout.power_law->coefficient] = f.zhou_mrr_weight_w * std::pow(f.zhou_rpm, *exponent);
      } else {
        o.power_weight = f.zhou_mrr_weight_w;
        o.power_base = f.zhou_rpm;
      }
    }
  }
  return out;
}

// Sum of squared residuals of the best linear fit at this offset (exponent fixed).
double profiled_sse(const PowerLog& log, const std::vector<OperatingSegment>& trace,
                    const PowerConstants& initial, const LogProblem& layout, double offset_s) {
  fit::Problem p;
  for (PP id : layout.ids) {
    fit::Parameter par;
    par.id = id;
    par.initial = get_parameter(initial, id);
    par.held = id == PP::ZhouC4;
    p.parameters.push_back(par);
  }
  p.observations = observations(log, trace, initial.model, layout, offset_s, initial.zhou.c4);
  std::vector<double> values(layout.ids.size());
  for (std::size_t j = 0; j < values.size(); ++j)
    values[j] = p.parameters[j].initial;
  return fit::linear_least_squares(p, values);
}

double median_step(const std::vector<double>& t) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < t.size(); ++i)
    steps.push_back(t[i] - t[i - 1]);
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  return steps[steps.size() / 2];
}

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = static_cast<double>(a.size());
  const double ma = std::accumulate(a.begin(), a.end(), 0.0) / n;
  const double mb = std::accumulate(b.begin(), b.end(), 0.0) / n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

// What the initial constants predict at every log time for a given offset; when they predict
// a flat line, the count of active features stands in so that the shape still correlates.
std::vector<double> predicted_shape(const PowerLog& log, const std::vector<OperatingSegment>& trace,
                                    const PowerConstants& initial, double offset_s, bool activity) {
  std::vector<double> out(log.t_s.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const OperatingPoint op = operating_point_at(trace, log.t_s[i] - offset_s);
    if (!activity) {
      out[i] = component_sum(component_power_w(initial, op));
    } else {
      double a = op.spindle_on + op.coolant_on + op.tool_change + (op.mrr_mm3_s > 0 ? 1 : 0);
      for (int k = 0; k < 3; ++k)
        a += op.axis_moving[k];
      out[i] = a;
    }
  }
  return out;
}

double estimate_offset(const PowerLog& log, const std::vector<OperatingSegment>& trace,
                       const PowerConstants& initial, const LogProblem& layout, double max_offset) {
  const double step = std::max(median_step(log.t_s), 1e-3);
  const bool flat = [&] {
    auto s = predicted_shape(log, trace, initial, 0.0, false);
    return *std::max_element(s.begin(), s.end()) - *std::min_element(s.begin(), s.end()) < 1e-9;
  }();
  double best = 0, best_score = -2;
  for (double offset = -max_offset; offset <= max_offset + 1e-12; offset += step) {
    const double score = pearson(predicted_shape(log, trace, initial, offset, flat), log.power_w);
    if (score > best_score) {
      best_score = score;
      best = offset;
    }
  }
  // Golden-section search of the least-squares misfit around the correlation peak.
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  double lo = best - 2 * step, hi = best + 2 * step;
  double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
  double f1 = profiled_sse(log, trace, initial, layout, x1);
  double f2 = profiled_sse(log, trace, initial, layout, x2);
  while (hi - lo > 1e-4) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - ratio * (hi - lo);
      f1 = profiled_sse(log, trace, initial, layout, x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + ratio * (hi - lo);
      f2 = profiled_sse(log, trace, initial, layout, x2);
    }
  }
  return 0.5 * (lo + hi);
}

double median_abs(std::vector<double> v) {
  for (double& x : v)
    x = std::abs(x);
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

} // namespace

LogFitResult fit_power_log(const PowerLog& log, const std::vector<OperatingSegment>& trace,
                           const PowerConstants& initial, const LogFitOptions& options) {
  LogFitResult result;
  result.constants = initial;
  if (log.t_s.size() < 3 || trace.empty()) {
    result.report.message = "a log fit needs at least 3 log rows and a program that runs";
    return result;
  }
  const PowerModel model = initial.model;
  const LogProblem layout = make_layout(model);
  result.offset_s = estimate_offset(log, trace, initial, layout, options.max_offset_s);

  // Starting values: linear least squares at the offset, the Zhou exponent fixed.
  fit::Problem linear;
  for (PP id : layout.ids) {
    fit::Parameter par;
    par.id = id;
    par.initial = get_parameter(initial, id);
    const bool asked_to_hold =
        std::find(options.hold.begin(), options.hold.end(), id) != options.hold.end();
    // A profile with a straight spindle line keeps it straight: a log at a few speeds cannot
    // tell the n^2 term from the n term.
    const bool straight_spindle = id == PP::SpindleKC && par.initial == 0;
    par.held = asked_to_hold || (id == PP::ZhouC4) || straight_spindle;
    linear.parameters.push_back(par);
  }
  linear.observations = observations(log, trace, model, layout, result.offset_s, initial.zhou.c4);
  std::vector<double> start(layout.ids.size());
  for (std::size_t j = 0; j < start.size(); ++j)
    start[j] = linear.parameters[j].initial;
  std::vector<bool> determined;
  fit::linear_least_squares(linear, start, &determined);

  fit::Problem problem;
  problem.power_law = layout.power_law;
  problem.observations = observations(log, trace, model, layout, result.offset_s, std::nullopt);
  std::vector<double> residuals;
  for (std::size_t i = 0; i < linear.observations.size(); ++i)
    residuals.push_back(fit::predict(linear, start, linear.observations[i]) -
                        linear.observations[i].y);
  for (std::size_t j = 0; j < layout.ids.size(); ++j) {
    const PP id = layout.ids[j];
    fit::Parameter par;
    par.id = id;
    par.initial = start[j];
    par.scale = std::abs(start[j]) > 0 ? std::abs(start[j]) : fallback_scale(id);
    if (is_zhou_parameter(id)) par.lower = 0.0;
    if (id == PP::ZhouC4) {
      par.held = !options.fit_zhou_exponent || !determined[problem.power_law->coefficient];
    } else {
      par.held = linear.parameters[j].held || !determined[j];
    }
    if (par.held && !linear.parameters[j].held && id != PP::ZhouC4)
      result.notes.push_back(std::string(parameter_info(id).key) +
                             ": the log cannot determine it; kept at its initial value");
    if (is_zhou_parameter(id) && par.initial < 0) par.initial = 0;
    problem.parameters.push_back(par);
  }
  problem.loss = options.loss;
  problem.loss_scale = options.loss_scale_w > 0
                           ? options.loss_scale_w
                           : std::max(1.5 * 1.4826 * median_abs(residuals), 1e-3);
  result.report = fit::solve(problem, "power log (" + log.path + ")");
  apply_fit(result.constants, result.report);
  return result;
}

} // namespace ncjoule
