// SeriesReducer, the power and MRR series: a point put again right after itself (a segment's
// end is the next one's start) is passed over once the series is bucketed. The result must be
// the one of a plain model of the reduction that puts every point.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "series_reducer.hpp"

using ncjoule::Series;
using ncjoule::estimate_detail::SeriesReducer;

namespace {

// The reduction as series_reducer.hpp describes it, every point put.
Series reduce(const std::vector<std::pair<double, double>>& points, std::size_t capacity) {
  struct Bucket {
    std::pair<double, double> low, high;
    bool used = false;
  };
  std::vector<std::pair<double, double>> raw;
  std::vector<Bucket> buckets;
  double t0 = 0, width = 0;
  auto put = [&](const std::pair<double, double>& p) {
    double index = std::floor((p.first - t0) / width);
    while (index >= double(capacity)) {
      for (std::size_t i = 0; i < capacity; ++i) {
        Bucket merged;
        for (std::size_t k = 2 * i; k < 2 * i + 2 && k < capacity; ++k) {
          if (!buckets[k].used) continue;
          if (!merged.used) {
            merged = buckets[k];
            continue;
          }
          if (buckets[k].low.second < merged.low.second) merged.low = buckets[k].low;
          if (buckets[k].high.second > merged.high.second) merged.high = buckets[k].high;
        }
        buckets[i] = merged;
      }
      width *= 2;
      index = std::floor((p.first - t0) / width);
    }
    Bucket& b = buckets[std::size_t(std::max(0.0, index))];
    if (!b.used) {
      b.low = b.high = p;
      b.used = true;
    } else {
      if (p.second < b.low.second) b.low = p;
      if (p.second > b.high.second) b.high = p;
    }
  };
  for (const auto& p : points) {
    if (buckets.empty()) {
      raw.push_back(p);
      if (raw.size() > 2 * capacity) {
        t0 = raw.front().first;
        const double span = raw.back().first - t0;
        width = span > 0 ? span / double(capacity) * 2 : 1e-9;
        buckets.assign(capacity, Bucket{});
        for (const auto& q : raw)
          put(q);
      }
    } else {
      put(p);
    }
  }
  Series s;
  if (buckets.empty()) {
    for (const auto& p : raw)
      s.t_s.push_back(p.first), s.value.push_back(p.second);
    return s;
  }
  for (const Bucket& b : buckets) {
    if (!b.used) continue;
    const auto& first = b.low.first <= b.high.first ? b.low : b.high;
    const auto& second = b.low.first <= b.high.first ? b.high : b.low;
    s.t_s.push_back(first.first), s.value.push_back(first.second);
    if (second != first) s.t_s.push_back(second.first), s.value.push_back(second.second);
  }
  return s;
}

} // namespace

TEST_CASE("the power series passes over a point put again and reduces as every point were put") {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> power(0, 5000);
  for (const std::size_t capacity : {2u, 7u, 50u, 2000u}) {
    CAPTURE(capacity);
    // Segments end to end, each end put again as the next start; some steps change nothing.
    std::vector<std::pair<double, double>> points;
    double t = 0, p = power(rng);
    for (int i = 0; i < 30000; ++i) {
      points.emplace_back(t, p);
      if (rng() % 5 != 0) t += 0.001 * double(1 + rng() % 50);
      if (rng() % 3 != 0) p = rng() % 7 == 0 ? -0.0 * p : power(rng);
      points.emplace_back(t, p);
    }
    SeriesReducer reducer(capacity);
    for (const auto& [time, value] : points)
      reducer.add(time, value);
    const Series got = reducer.result();
    const Series expected = reduce(points, capacity);
    REQUIRE(got.t_s.size() == expected.t_s.size());
    int differ = 0;
    for (std::size_t i = 0; i < got.t_s.size(); ++i)
      differ += got.t_s[i] != expected.t_s[i] || got.value[i] != expected.value[i];
    CHECK(differ == 0);
    CHECK(got.t_s.size() >= std::min<std::size_t>(capacity, 100));
  }
}
