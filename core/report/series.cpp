// Power and removal rate over time, and their reduction to what a chart can draw.
#include <algorithm>
#include <cmath>

#include "ncjoule/report.hpp"

namespace ncjoule {

Series downsample_min_max(const Series& in, std::size_t max_points) {
  max_points = std::max<std::size_t>(max_points, 4);
  const std::size_t n = std::min(in.t_s.size(), in.value.size());
  if (n <= max_points) return in;
  const std::size_t buckets = max_points / 2;
  const double t0 = in.t_s.front();
  const double span = in.t_s[n - 1] - t0;
  Series out;
  std::size_t i = 0;
  for (std::size_t b = 0; b < buckets && i < n; ++b) {
    const double end = b + 1 == buckets ? INFINITY : t0 + span * double(b + 1) / double(buckets);
    std::size_t lo = i, hi = i;
    for (; i < n && (in.t_s[i] < end || i == lo); ++i) {
      if (in.value[i] < in.value[lo]) lo = i;
      if (in.value[i] > in.value[hi]) hi = i;
    }
    const std::size_t first = std::min(lo, hi), second = std::max(lo, hi);
    out.t_s.push_back(in.t_s[first]);
    out.value.push_back(in.value[first]);
    if (second != first) {
      out.t_s.push_back(in.t_s[second]);
      out.value.push_back(in.value[second]);
    }
  }
  return out;
}

} // namespace ncjoule
