// Internal: the program's power and MRR over time, and its toolpath, reduced as they come to a
// few thousand points, so that a long program needs no more memory for them than a short one.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "ncjoule/estimate.hpp"

namespace ncjoule::estimate_detail {

// Points in time order, reduced to at most about 2 * `buckets`: the time axis is cut into equal
// buckets, each keeping its lowest and highest point (in time order), so peaks and dips survive.
// The span is not known in advance: points are kept as they are until there are too many, then
// bucketed, and the bucket width doubles (pairs of buckets merge) whenever the points run past
// the last bucket. A series short enough comes back unchanged.
class SeriesReducer {
public:
  explicit SeriesReducer(std::size_t buckets = 2000);
  void add(double t_s, double value);
  Series result() const;

private:
  struct Point {
    double t = 0, v = 0;
  };
  struct Bucket {
    Point low, high;
    bool used = false;
  };
  void start_buckets();
  void put(const Point& p);
  void widen();

  std::size_t capacity_;
  std::vector<Point> raw_;
  std::vector<Bucket> buckets_;
  bool bucketed_ = false;
  double t0_ = 0, width_ = 0;
  Point last_{std::nan(""), 0}; // the point put last once bucketed (none: NaN, equal to none)
};

// The toolpath for drawing, reduced to at most about `max_points`: a point is kept when the tool
// has gone `tolerance` from the last one kept, when the motion changes between rapid and feed, or
// when the power changes by a tenth; when too many are kept, the tolerances double and the kept
// points are thinned again. Should that not be enough (rapid and feed alternate on every move),
// every other point is dropped, so that thinning stays rare and adding a point cheap.
class PathReducer {
public:
  explicit PathReducer(std::size_t max_points = 12000);
  void add(const PathPoint& point);
  std::vector<PathPoint> result() const;

private:
  bool keeps(const PathPoint& last, const PathPoint& p) const;
  void thin();

  std::size_t max_points_;
  double tolerance_mm_ = 0.05;
  double power_tolerance_ = 0.1; // relative
  std::vector<PathPoint> points_;
  PathPoint pending_; // the latest point, kept at the end whatever the tolerance
  bool has_pending_ = false;
};

} // namespace ncjoule::estimate_detail
