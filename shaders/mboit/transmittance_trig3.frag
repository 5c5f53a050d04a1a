// transmittance_trig3.frag: mboit's "transmittance" pass, trig3 (mboit/transmittance.glsl).
#include "common/oit_shared.h"
#define MBOIT_VARIANT OIT_MBOIT_TRIG3
#include "mboit/transmittance.glsl"
