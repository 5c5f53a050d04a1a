// distance_max.frag: blend_distance.frag writing the larger distance (first
// sweep of the distance modulation with an automatic focus region).
#define DISTANCE_MAX 1
#include "ddp/blend_distance.frag"
