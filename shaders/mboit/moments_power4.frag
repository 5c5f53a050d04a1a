// moments_power4.frag: mboit's "moments" pass, power4 (mboit/moments.glsl).
#include "common/oit_shared.h"
#define MBOIT_VARIANT OIT_MBOIT_POWER4
#include "mboit/moments.glsl"
