#pragma once
// The analytic shapes' primitives and their exact intersection routines (double precision):
// each lives in its kind's file.

#include "accel/kinds/plane.h"
#include "accel/kinds/sphere.h"
#include "accel/kinds/triangle.h"
