// variants.glsl: the compile-time switches of the program variants
// (oit_gl_program_variant in src/core/gl_util.h). Each defaults to the general
// program, with the feature in; the C side compiles a narrower variant for the
// frames that do not use it. Why not a branch on a uniform: llvmpipe runs both
// sides of every branch with a lane mask, uniform or not, so a feature that is
// off but compiled in costs about what it costs when on (docs/algorithms.md,
// "Where ll's time goes").
#ifndef OIT_VARIANTS_GLSL
#define OIT_VARIANTS_GLSL

// the distance modulation (u_distance_mode >= 0; docs/modulation.md)
#ifndef OIT_VARIANT_DISTANCE
#define OIT_VARIANT_DISTANCE 1
#endif
// the buffer views other than the colour image (heat map, peel limit, layer)
#ifndef OIT_VARIANT_VIEWS
#define OIT_VARIANT_VIEWS 1
#endif
// the Illustration Buffer's modulations that read the neighbours' results
// (curvature, distance, dist-curv, edges, fields; ib/compose.frag)
#ifndef OIT_VARIANT_IB_MODES
#define OIT_VARIANT_IB_MODES 1
#endif

#endif
