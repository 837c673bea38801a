#include "sculpt/core/volume/volume.h"
#include "sculpt/hal/pose/pose.h"
