// distance_max.frag: blend_distance.frag writing the distance (first sweep of
// the distance modulation with an automatic focus region).
#define DISTANCE_MAX 1
#include "dp/blend_distance.frag"
