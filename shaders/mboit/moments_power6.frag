// moments_power6.frag: mboit's "moments" pass, power6 (mboit/moments.glsl).
#include "common/oit_shared.h"
#define MBOIT_VARIANT OIT_MBOIT_POWER6
#include "mboit/moments.glsl"
