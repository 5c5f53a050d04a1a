// transmittance_power6.frag: mboit's "transmittance" pass, power6 (mboit/transmittance.glsl).
#include "common/oit_shared.h"
#define MBOIT_VARIANT OIT_MBOIT_POWER6
#include "mboit/transmittance.glsl"
