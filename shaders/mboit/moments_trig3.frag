// moments_trig3.frag: mboit's "moments" pass, trig3 (mboit/moments.glsl).
#include "common/oit_shared.h"
#define MBOIT_VARIANT OIT_MBOIT_TRIG3
#include "mboit/moments.glsl"
