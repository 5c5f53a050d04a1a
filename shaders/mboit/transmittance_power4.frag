// transmittance_power4.frag: mboit's "transmittance" pass, power4 (mboit/transmittance.glsl).
#include "common/oit_shared.h"
#define MBOIT_VARIANT OIT_MBOIT_POWER4
#include "mboit/transmittance.glsl"
