#include "rotation.h"

#include "trig.h"

namespace impulse {

Rotation rotation_of(double angle) {
    return {cosine(angle), sine(angle)};
}

} // namespace impulse
