// The SVG pictures, for the files that draw both kinds: one run's motion
// (motion_picture.h) and golden versus new (comparison_picture.h).
#pragma once

#include "comparison_picture.h"
#include "motion_picture.h"
