// The solid a 3-axis tool sweeps along one straight step, asked two ways:
//  - by column: the lowest point of the tool's lower surface over the whole step at (x, y)
//    (what the dexel engine clips to), found exactly, not only at the step's end points;
//  - by point: whether a point lies inside the swept tool (what the voxel engine tests),
//    worked out from the tool's cross-section radius at the point's height.
// Both use that, along a straight step, the quantity minimised is convex in the position along
// the step for every supported profile (flat, ball, bull nose, cone), so a closed form or a
// golden-section search finds the true minimum.
#pragma once

#include "ncjoule/removal.hpp"

namespace ncjoule::detail {

class SweptStep {
public:
  SweptStep(const Tool& tool, const Point3& from, const Point3& to);

  // Lowest Z of the tool's lower surface over the step in the column through (x, y);
  // +infinity when the tool never covers that column.
  double envelope_at(double x, double y) const;
  // Whether (x, y, z) is inside the tool at some position of the step.
  bool contains(double x, double y, double z) const;

  // The columns the step may touch: on the row at y, centres with x in [xlo, xhi].
  bool row_span(double y, double& xlo, double& xhi) const;
  double footprint_ymin() const { return ymin_; }
  double footprint_ymax() const { return ymax_; }
  double footprint_xmin() const { return xmin_; }
  double footprint_xmax() const { return xmax_; }
  double lowest_tip_z() const { return zlow_; }

  // A vertical step (plunge or retract: the tool axis does not move sideways).
  bool vertical() const { return len_ == 0; }
  // Whether `other` is a vertical step of the same tool on the same axis as this one: the two
  // cover the same columns, each down to its own lowest tip plus the same offset per column.
  bool same_axis(const SweptStep& other) const {
    return vertical() && other.vertical() && &tool_ == &other.tool_ && ax_ == other.ax_ &&
           ay_ == other.ay_;
  }
  // For a vertical step: the lowest tool bottom in the column through (x, y) above the lowest
  // tip (+infinity where the tool does not cover it). envelope_at(x, y) is
  // lowest_tip_z() + plunge_offset(x, y), the same number bit for bit.
  double plunge_offset(double x, double y) const;

private:
  // Lowest tool bottom over the step for a profile of radius `radius` (the cutter, or the
  // shank seen as a flat tool), relative to the tip.
  double lowest_bottom(double x, double y, bool shank) const;
  double profile_height(double r) const; // cutter profile, r clamped to the radius

  const Tool& tool_;        // outlives the step: a step is built and used within one call
  double ax_, ay_, az_;     // start of the step
  double dz_;               // rise over the step
  double len_;              // XY length of the step
  double ux_ = 0, uy_ = 0;  // XY unit direction (0 when the step is vertical)
  double slope_ = 0;        // dz per mm of XY travel
  double slope_norm_ = 1;   // sqrt(1 + slope^2): the ball's stationary point
  double radius_;           // cutter radius
  double shank_radius_ = 0; // > radius_ when a wider shank can touch the stock
  double shank_height_ = 0; // height of the shank's bottom above the tip
  double reach_;            // widest radius that can touch
  double tan_half_ = 0;     // drill and chamfer: tan(half tip angle)
  double tip_radius_ = 0;   // chamfer: radius of the flat at its tip
  double zlow_;             // lowest tip Z of the step
  double xmin_, xmax_, ymin_, ymax_;
};

} // namespace ncjoule::detail
