#include "common/scene/rigid_animation.h"

namespace hybridlab {

Transform RigidAnimation::at(double t) const {
    Transform tr;
    tr.position = interpolate(times, positions, t, interpolation);
    tr.rotation = interpolate(times, rotations, t);
    tr.scale = interpolate(times, scales, t, interpolation);
    return tr;
}

}  // namespace hybridlab
