// The sampled path of a timed move: points no further apart than PlanOptions allows, in space
// and in time, placed on the move's own path (arcs follow the arc), each with the time the
// velocity profile gives for its distance along the move.
#pragma once

#include <vector>

#include "dog_leg.hpp"
#include "ncjoule/kinematics.hpp"
#include "timed_span.hpp"

namespace ncjoule::kinematics_detail {

// `spatial_length` is the move's length in mm (0 for moves of rotary axes only, which are
// sampled in time only). The programmed path is laid onto the timed stretch in proportion to
// distance: where blend arcs shorten the timed path, a sample's position stays on the
// programmed path and its time is the one of the same fraction of the stretch.
void sample_move(const CanonCommand& move, const TimedSpan& profile, double spatial_length,
                 double start_s, const PlanOptions& options, std::vector<MotionSample>& out);

void sample_dog_leg(const CanonCommand& move, const DogLegMove& dog_leg, double start_s,
                    const PlanOptions& options, std::vector<MotionSample>& out);

} // namespace ncjoule::kinematics_detail
