/*
 * oit_shared.h: the one place where buffer layouts, binding points and limits
 * shared by the C core and the GLSL shaders are defined.
 *
 * This file is included by C (src/core, via the include path) and by every
 * shader (the shader loader expands `#include "common/oit_shared.h"`).
 * It must therefore stay valid in both languages: only #define of integer
 * literals, #ifndef guards and comments.
 */
#ifndef OIT_SHARED_H
#define OIT_SHARED_H

/* ---- vertex attribute locations (common/geometry.vert) ---- */
#define OIT_ATTRIB_POSITION 0  /* vec3, model space */
#define OIT_ATTRIB_NORMAL 1    /* vec3, model space */
#define OIT_ATTRIB_COMPONENT 2 /* uint, index into the component table */
#define OIT_ATTRIB_WELDED_ID 3 /* uint, position-welded vertex id */

/* ---- shader storage buffer bindings ---- */
/* vec4 per component: rgb = material colour, a = material opacity */
#define OIT_SSBO_COMPONENTS 0
/* linked lists: fragment nodes and their next pointers (see alg_ll.c) */
#define OIT_SSBO_FRAGMENT_NODES 1
#define OIT_SSBO_FRAGMENT_NEXT 2
/* second next-pointer buffer for the in-place insertion sort */
#define OIT_SSBO_FRAGMENT_SORTED_NEXT 3
/* per-frame counters: [0] fragments requested, [1] longest list, [2] pixels with fragments */
#define OIT_SSBO_FRAME_COUNTERS 4
#define OIT_FRAME_COUNTER_FRAGMENTS 0
#define OIT_FRAME_COUNTER_MAX_LIST 1
#define OIT_FRAME_COUNTER_NONEMPTY_PIXELS 2
#define OIT_FRAME_COUNTER_COUNT 4
/* ll local-array sort: pixels whose list was longer than OIT_LOCAL_ARRAY_CAPACITY
 * and were sorted in place instead (uses the spare slot 3) */
#define OIT_FRAME_COUNTER_LONG_LIST_PIXELS 3

/* ---- per-pixel linked lists (alg_ll.c, shaders/ll/ll_nodes.glsl) ----
 * Node i of the fragment pool is one uvec4 in OIT_SSBO_FRAGMENT_NODES:
 *   x = packUnorm2x16(r, g), y = packUnorm2x16(b, a)   shaded colour, straight alpha, 16 bit
 *   z = floatBitsToUint(oit_canonical_depth())         depth along the pixel's ray, [0, 1]
 *   w = gl_PrimitiveID                                 triangle index (depth tie-break)
 * Its next pointers are uint i of OIT_SSBO_FRAGMENT_NEXT (list as filled) and of
 * OIT_SSBO_FRAGMENT_SORTED_NEXT (list sorted front to back); OIT_LIST_END ends a list. */
#define OIT_LL_NODE_BYTES 16
#define OIT_LL_NEXT_BYTES 4
/* ll: read-only views of the pool as buffer textures, for the passes that only
 * read a buffer (texelFetch is gathered in SIMD on llvmpipe; storage-buffer
 * loads go lane by lane): the sort reads nodes and next, compose nodes and
 * sorted next */
#define OIT_TEXUNIT_LL_NODES 16        /* usamplerBuffer rgba32ui over the nodes */
#define OIT_TEXUNIT_LL_NEXT 17         /* usamplerBuffer r32ui over next */
#define OIT_TEXUNIT_LL_SORTED_NEXT 18  /* usamplerBuffer r32ui over sorted next */
/* ll counters (uint, OIT_SSBO_FRAME_COUNTERS): [0..3] as OIT_FRAME_COUNTER_*, then: */
/* (ll leaves [2] unused: its non-empty pixels are the histogram's sum) */
/* non-empty pixels whose list is longer than 2/3 of the longest, counted by
 * compose only when the longest list is in the histogram's open last bin;
 * otherwise the C side sums the histogram's bins above 2/3 of the longest */
#define OIT_LL_COUNTER_PSI_PIXELS 4
#define OIT_LL_COUNTER_HISTOGRAM 5   /* OIT_LL_HISTOGRAM_BINS bins: pixels per list length (bin 0 unused) */
#define OIT_LL_HISTOGRAM_BINS 65     /* == OIT_HISTOGRAM_BINS in oit.h: lengths 0..63, then 64 or more */
/* distance modulation: floatBitsToUint of the frame's largest distance */
#define OIT_LL_COUNTER_MAX_DISTANCE 70
/* times the 32-bit fragment counter wrapped past 0xFFFFFFFF in the fill: the
 * high word of the frame's 64-bit fragment count (a frame past
 * OIT_MAX_FRAME_FRAGMENTS is an error, never a wrapped index) */
#define OIT_LL_COUNTER_FRAGMENTS_WRAPS 71
/* fragments the sort walked in lists of the histogram's open last bin (64 or
 * more); with sum(length * pixels) over the other bins, the fragments sorted.
 * Fewer than were stored means a shader loop was cut short (llvmpipe ends a
 * loop after 65535 iterations), and the frame is an error, not an image
 * missing fragments */
#define OIT_LL_COUNTER_SORTED_FRAGMENTS 72
#define OIT_LL_COUNTER_COUNT 73
/* ll compose: what it shows (the numbers of oit_view) and its parameter (int) */
#define OIT_LL_VIEW_COLOUR 0
#define OIT_LL_VIEW_HEATMAP 1
#define OIT_LL_VIEW_PEEL_LIMIT 2
#define OIT_LL_VIEW_LAYER 3

/* ---- k closest layers: kbuffer and hybrid (src/core/closest_layers.c,
 * shaders/common/closest_layers.glsl) ----
 * Each pixel p = y * width + x owns k slots, slot i of it at index p * k + i of
 * OIT_SSBO_CLOSEST_SLOTS, one uvec4 each:
 *   x = key: floatBitsToUint(canonical depth) (in [0, 1], so the bits order as
 *       the floats), OIT_CLOSEST_EMPTY_KEY while empty
 *   y = owner: the triangle index + 1 of the fragment that claimed the slot, 0 while unclaimed
 *   z = packUnorm2x16(r, g), w = packUnorm2x16(b, a): its shaded colour, as ll stores it
 * After the select pass a pixel's keys are its k smallest, ascending. */
#define OIT_SSBO_CLOSEST_SLOTS 1
#define OIT_CLOSEST_SLOT_BYTES 16
#define OIT_CLOSEST_EMPTY_KEY 0xFFFFFFFFu
/* uint per pixel: the fragments the store pass sent to the tail (for the list lengths) */
#define OIT_SSBO_CLOSEST_TAIL_COUNTS 2
#define OIT_CLOSEST_TAIL_COUNT_BYTES 4
/* counters (uint): fragments kept in the core, sent to the tail, the longest
 * list, non-empty pixels, then a histogram of list lengths */
#define OIT_SSBO_CLOSEST_COUNTERS 4
#define OIT_CLOSEST_COUNTER_CORE 0
#define OIT_CLOSEST_COUNTER_TAIL 1
#define OIT_CLOSEST_COUNTER_MAX_LIST 2
#define OIT_CLOSEST_COUNTER_NONEMPTY_PIXELS 3
#define OIT_CLOSEST_COUNTER_HISTOGRAM 4 /* OIT_CLOSEST_HISTOGRAM_BINS bins, bin 0 unused */
#define OIT_CLOSEST_HISTOGRAM_BINS 65   /* == OIT_HISTOGRAM_BINS in oit.h */
#define OIT_CLOSEST_COUNTER_COUNT 69
/* the tail's float targets, read by compose (kbuffer: one, premultiplied
 * "over"; hybrid: sum of (c a, a) and product of (1 - a)) */
#define OIT_TEXUNIT_CLOSEST_TAIL 2
#define OIT_TEXUNIT_CLOSEST_TAIL_PRODUCT 3

/* ---- image units ---- */
#define OIT_IMAGE_LIST_HEAD 0  /* r32ui, one list head per pixel */
#define OIT_IMAGE_LIST_COUNT 1 /* r32ui, fragments per pixel */
/* anti-aliasing (common/samples_accumulate.comp, gpu_algorithm.c): the
 * RGBA8 output viewed as rgba8ui, and the per-pixel sum of the samples
 * (rgba16ui: 16 samples x 255 fit) */
#define OIT_IMAGE_SAMPLES_OUTPUT 4
#define OIT_IMAGE_SAMPLES_SUM 5
#define OIT_SAMPLES_STORE 0   /* the first sample: sum = output */
#define OIT_SAMPLES_ADD 1     /* sum += output */
#define OIT_SAMPLES_RESOLVE 2 /* the last: output = (sum + output + n / 2) / n */

/* ---- texture units ---- */
#define OIT_TEXUNIT_DEPTH_PREVIOUS 0 /* depth peeling: depth of the layer peeled last */
#define OIT_TEXUNIT_DEPTH_MINMAX 1   /* dual depth peeling: (-near, far) of remaining layers */
#define OIT_TEXUNIT_ACCUM_FRONT 2
#define OIT_TEXUNIT_ACCUM_BACK 3
#define OIT_TEXUNIT_ACCUM 4          /* weighted blended: sum of weighted premultiplied colour */
#define OIT_TEXUNIT_REVEALAGE 5      /* weighted blended: product of (1 - alpha) */
#define OIT_TEXUNIT_PEEL_LAYER 6     /* peeling: colour of the layer just peeled (dp), of the back layer (ddp) */
/* peeling with the distance modulation (delayed blending): the colour and depth
 * of the layer peeled after the one being blended */
#define OIT_TEXUNIT_PEEL_NEXT_LAYER 7
#define OIT_TEXUNIT_DEPTH_NEXT 8
/* dp with curvature (neighbours in the same peeled layer): the layer's octahedral
 * normal and component + 1 (rg32ui, 0 = no fragment) */
#define OIT_TEXUNIT_PEEL_NORMAL 13

/* ---- limits ---- */
/* the end-of-list marker in list heads and next pointers */
#define OIT_LIST_END 0xFFFFFFFFu
/* ll, ib: the most fragments one frame may have: node indices are 32-bit and
 * OIT_LIST_END is reserved (the fill counts in 64 bits, see
 * OIT_LL_COUNTER_FRAGMENTS_WRAPS, so a frame past it is an error) */
#define OIT_MAX_FRAME_FRAGMENTS 0xFFFFFFFFu
/* every GPU algorithm: the widest and tallest image (oit_gl_output_resize), so
 * that per-pixel counters (pixels with fragments, histogram bins) stay below
 * 2^32 and ib's epsilon queue can pack a pixel as x | y << 16 */
#define OIT_MAX_IMAGE_SIDE 65535
/* local-array sort: the longest list that can be sorted in registers */
#define OIT_LOCAL_ARRAY_CAPACITY 64
/* ll --sort bma (shaders/ll/sort_bma.frag): the register block (nodes sorted in
 * registers by a network), the largest private array (lists of 9..16, 17..32,
 * 33..64 nodes get arrays of 16, 32, 64), and the levels of the merge in the
 * lists for longer ones (runs of 8 << level nodes; 29 levels reach 2^32) */
#define OIT_LL_BMA_BLOCK 8
#define OIT_LL_BMA_LARGEST_ARRAY 64
#define OIT_LL_BMA_LEVELS 30
/* kbuffer, hybrid, mlab: the layers kept per pixel (oit_algorithm_config.layers)
 * by default and at most (shader-local arrays are sized by the maximum) */
#define OIT_APPROX_LAYERS_DEFAULT 8
#define OIT_APPROX_LAYERS_MAX 64
/* peeling: the most layers one frame may peel (each is one timed stage) */
#define OIT_MAX_PEEL_LAYERS 256

/* ---- moment-based OIT (alg_mboit.c, shaders/mboit/) ----
 * The variants, the numbers of oit_moments in oit.h; each variant's shaders
 * define MBOIT_VARIANT as one of them before including mboit/common.glsl. */
#define OIT_MBOIT_POWER4 1
#define OIT_MBOIT_POWER6 2
#define OIT_MBOIT_TRIG3 3
/* the "moments" pass's colour attachments (= fragment output locations):
 * b0 (r32f: the pixel's total optical depth), moments 1..4 (rgba32f; trig3:
 * real and imaginary parts of moments 1 and 2) and, for power6 and trig3,
 * moments 5, 6 (rg32f; trig3: moment 3) */
#define OIT_MBOIT_TARGET_B0 0
#define OIT_MBOIT_TARGET_MOMENTS 1
#define OIT_MBOIT_TARGET_EXTRA 2
/* the same textures read by the "transmittance" and "compose" passes, and the
 * transmittance pass's accumulation (rgba32f: sum T a c, sum T a) */
#define OIT_TEXUNIT_MBOIT_B0 24
#define OIT_TEXUNIT_MBOIT_MOMENTS 25
#define OIT_TEXUNIT_MBOIT_EXTRA 26
#define OIT_TEXUNIT_MBOIT_ACCUM 27

/* ---- wavelet transparency (alg_wavelet.c, shaders/wavelet/) ----
 * The rank R, 1..OIT_WAVELET_RANK_MAX (oit.h's OIT_WAVELET_RANK_MAX is the same):
 * 2^(R+1) Haar coefficients per pixel in 2^(R+1) / 4 rgba32f targets. The most
 * is 3 (16 coefficients): 4 targets and b0 make 5 colour attachments; rank 4
 * would need 9, and GL 4.3 promises only 8 draw buffers.
 * The "coefficients" pass's colour attachments (= fragment output locations):
 * b0 (r32f: the pixel's total optical depth, as mboit's), then the coefficient
 * targets from OIT_WAVELET_TARGET_COEFFICIENTS on. The passes after it read b0
 * and the accumulation at mboit's units (its compose.frag is wavelet's), and
 * coefficient target t at OIT_TEXUNIT_WAVELET_COEFFICIENTS + t (9..12: ib's
 * units, which no wavelet program declares). */
#define OIT_WAVELET_RANK_MAX 3
#define OIT_WAVELET_TARGET_B0 0
#define OIT_WAVELET_TARGET_COEFFICIENTS 1
#define OIT_TEXUNIT_WAVELET_COEFFICIENTS 9

/* ---- stochastic transparency (alg_stochastic.c, shaders/stochastic/) ----
 * Per pixel S depth slots (uint: floatBitsToUint of the window depth, which
 * orders as the depth for depths in [0, 1]; OIT_STOCHASTIC_EMPTY: no sample
 * covered), slot s of pixel p at index p * S + s of OIT_SSBO_STOCHASTIC_DEPTH. */
#define OIT_SSBO_STOCHASTIC_DEPTH 1
#define OIT_STOCHASTIC_EMPTY 0xFFFFFFFFu
#define OIT_STOCHASTIC_SAMPLES_MAX 16
/* the pixel's sample count S (int), the seed (uint), the masks (int: OIT_STOCHASTIC_MASKS_*) */
#define OIT_UNIFORM_STOCHASTIC_SAMPLES 16
#define OIT_UNIFORM_STOCHASTIC_SEED 17
#define OIT_UNIFORM_STOCHASTIC_MASKS 18
#define OIT_STOCHASTIC_MASKS_STRATIFIED 1
#define OIT_STOCHASTIC_MASKS_INDEPENDENT 2

/* ---- the frame's parameters: one std140 uniform block (common/frame.glsl) ----
 * uploaded once per frame (oit_gpu_frame_begin: gl_util.h's oit_frame_block,
 * which asserts these byte offsets; every program's are checked against them
 * when it is linked). Every pass reads it at binding OIT_UBO_FRAME:
 * the matrices (mat4; the normal matrix a mat3 of three vec4 columns), the
 * background (vec3) and the frame's opacity multiplier, the local modulation
 * (docs/modulation.md): focus shape (OIT_FOCUS_SHAPE_*), its two vec4 of
 * parameters (point xyz | plane abcd | box min; box max), fall-off length,
 * contrast, and the distance along the ray (dp, ddp, ll; ib has its own): mode
 * (OIT_IB_DISTANCE_*, -1 when the frame's modulation is not distance), skip k,
 * and the normalising length (the focus region, or the frame's largest
 * distance once an algorithm knows it: it writes that field alone). The sort
 * depth of every exact algorithm (common/canonical_depth.glsl) takes
 * model-space planes to eye space with plane_to_eye, transpose(inverse(modelview)). */
#define OIT_UBO_FRAME 0
#define OIT_FRAME_MODELVIEW 0
#define OIT_FRAME_PROJECTION 64
#define OIT_FRAME_PLANE_TO_EYE 128
#define OIT_FRAME_INVERSE_MODELVIEW 192
#define OIT_FRAME_INVERSE_PROJECTION 256
#define OIT_FRAME_NORMAL_MATRIX 320
#define OIT_FRAME_BACKGROUND 368
#define OIT_FRAME_ALPHA 380
#define OIT_FRAME_FOCUS_A 384
#define OIT_FRAME_FOCUS_B 400
#define OIT_FRAME_VIEWPORT 416
#define OIT_FRAME_SHADING 424
#define OIT_FRAME_FOCUS_SHAPE 428
#define OIT_FRAME_FOCUS_REGION 432
#define OIT_FRAME_CONTRAST 436
#define OIT_FRAME_DISTANCE_MODE 440
#define OIT_FRAME_DISTANCE_SKIP 444
#define OIT_FRAME_DISTANCE_NORM 448
/* section planes (docs/sections.md): how many (0..OIT_SECTIONS_MAX), whether
 * they cut every part (1) or only those the per-part buffer texture at
 * OIT_TEXUNIT_LOCAL_PART_SECTION marks (0), and the planes in eye space:
 * vec4 q per plane, a fragment at eye position e is removed where
 * dot(q.xyz, e) + q.w > 0 (oit_section_eye_planes, sections.c) */
#define OIT_FRAME_SECTION_COUNT 452
#define OIT_FRAME_SECTION_ALL_PARTS 456
#define OIT_FRAME_SECTION_PLANES 464
#define OIT_FRAME_BLOCK_BYTES 560
/* per-part opacity (oit_local_modulation.component_alpha): no uniform, a buffer
 * texture (samplerBuffer, r32f) with one float per part of the model, every
 * part (1 where the frame sets none), filled each frame by
 * oit_gl_bind_part_alpha (gl_frame.c) and read by oit_local_alpha */
#define OIT_TEXUNIT_LOCAL_PART_ALPHA 23
/* selection highlight (oit_local_modulation.component_highlight): a buffer
 * texture (samplerBuffer, rgba32f), per part the highlight colour and its
 * weight (0: not highlighted), filled each frame by oit_gl_bind_part_alpha and
 * read by oit_local_tint: material rgb' = mix(rgb, highlight rgb, weight) */
#define OIT_TEXUNIT_LOCAL_PART_TINT 28
/* which parts the section planes cut (oit_local_modulation.section_parts): a
 * buffer texture (usamplerBuffer, r8ui), per part 1 (cut) or 0, filled each
 * frame by oit_gl_bind_part_alpha when the frame names parts, read by
 * oit_section_removed (common/local_modulation.glsl) */
#define OIT_TEXUNIT_LOCAL_PART_SECTION 29
/* the highlight's defaults (oit_local_highlight): an orange, mixed in at 60% */
#define OIT_HIGHLIGHT_COLOUR_R_PERCENT 100
#define OIT_HIGHLIGHT_COLOUR_G_PERCENT 55
#define OIT_HIGHLIGHT_COLOUR_B_PERCENT 0
#define OIT_HIGHLIGHT_STRENGTH_PERCENT 60
/* a plane is seen edge-on from a pixel when its normal is within 1e-6 (in
 * millionths) of perpendicular to the pixel's ray: the interpolated depth is kept */
#define OIT_EDGE_ON_PLANE_PPM 1
/* the canonical depth is clamped to [0, this]: the largest float below 1, so a
 * fragment whose plane meets its ray at or beyond the far plane (a plane that
 * fits a nearly edge-on triangle only within the coplanar tolerance) still
 * passes dp's depth test against the cleared 1.0, as every list keeps it */
#define OIT_CANONICAL_DEPTH_MAX 0.999999940395355224609375
/* section planes (oit_local_modulation.sections; docs/sections.md): at most
 * this many at once */
#define OIT_SECTIONS_MAX 6
/* The component vertex attribute carries, above these bits, 1 + the section
 * whose cap the vertex belongs to (oit_model.vertex_section_cap; 0: not a cap):
 * geometry.vert splits it off; parts number below 1 << this */
#define OIT_COMPONENT_CAP_SHIFT 28
/* focus shapes (oit_focus_shape in oit.h) */
#define OIT_FOCUS_SHAPE_NONE 0
#define OIT_FOCUS_SHAPE_POINT 1
#define OIT_FOCUS_SHAPE_PLANE 2
#define OIT_FOCUS_SHAPE_BOX 3
/* algorithm-specific uniforms start here */
#define OIT_UNIFORM_ALGORITHM_BASE 16
/* ll fill: the fragment pool's capacity in nodes (uint); literal because GLSL 4.30
 * layout qualifiers take literals only */
#define OIT_UNIFORM_LL_POOL_CAPACITY 16
/* ll compose: OIT_LL_VIEW_* (int) and the view's parameter (int) */
#define OIT_UNIFORM_LL_VIEW 17
#define OIT_UNIFORM_LL_VIEW_PARAMETER 18
/* ll compose with the distance modulation: 0 normalise by u_distance_norm, 1 only
 * find the frame's largest distance, 2 normalise by it (int) */
#define OIT_UNIFORM_LL_DISTANCE_PASS 19
/* kbuffer, hybrid: k, the layers kept per pixel (int) */
#define OIT_UNIFORM_CLOSEST_LAYERS 16
/* dp peel: 0 for the first layer (nothing to peel against), 1 after (int) */
#define OIT_UNIFORM_DP_HAS_PREVIOUS 16
/* dp curvature blend: curvature effect (float), neighbours 4 or 8 (int), the
 * modulation (int: OIT_IB_MODE_CURVATURE, _DIST_CURV or _EDGES) */
#define OIT_UNIFORM_DP_CURVATURE_EFFECT 17
#define OIT_UNIFORM_DP_CURVATURE_NEIGHBOURS 18
#define OIT_UNIFORM_DP_NEIGHBOUR_MODE 19
/* ddp peel: 0 on a last pass that may peel only one more layer (odd layer limit), else 1 (int) */
#define OIT_UNIFORM_DDP_PEEL_BACK 16
/* ddp probe: 0 counts pixels with layers left, 1 those with two or more distinct depths (int) */
#define OIT_UNIFORM_DDP_PROBE_TWO 17

/* shading modes (oit_shading in C) */
#define OIT_SHADING_FLAT 0
#define OIT_SHADING_HEADLIGHT 1

/* headlight: colour * (ambient + diffuse * |n . v|), two-sided */
#define OIT_HEADLIGHT_AMBIENT_PERCENT 25

/* ---- Illustration Buffer (alg_ib.c, shaders/ib/ib_common.glsl) ----
 * Per pixel: OIT_IMAGE_LIST_HEAD holds the list head during the fill and the
 * start of the pixel's sorted run afterwards; OIT_IMAGE_LIST_COUNT its length.
 * Per fragment (a fill node, then a slot of a sorted run; layouts in ib_common.glsl):
 *   nodes      uvec4: fill node (depth, triangle, normal, next); after the sort the
 *              two ping-pong copies of the transparency fields
 *   run core   uvec4: depth, triangle, octahedral normal, curvature | distance
 *   run links  uvec2: four 16-bit neighbour layer indices (left, right, bottom, top) */
#define OIT_SSBO_IB_NODES 1
#define OIT_SSBO_IB_RUN_CORE 5
#define OIT_SSBO_IB_RUN_LINKS 6
#define OIT_SSBO_IB_COUNTERS 7
#define OIT_SSBO_IB_PARAMS 8
#define OIT_SSBO_IB_INDICES 9          /* the scene's index buffer: 3 uint per triangle */
#define OIT_SSBO_IB_WELDED 10          /* the scene's welded-id vertex buffer */
#define OIT_SSBO_IB_POSITIONS 11       /* the scene's position vertex buffer: 3 float per vertex */
#define OIT_SSBO_IB_VERTEX_COMPONENT 12 /* the scene's component vertex buffer */
/* ib: read-only views of ib buffers as buffer textures (texelFetch is gathered
 * in SIMD on llvmpipe; storage-buffer loads go lane by lane) */
#define OIT_TEXUNIT_IB_RUN_CORE 9      /* usamplerBuffer rgba32ui over the run core */
#define OIT_TEXUNIT_IB_RUN_LINKS 10    /* usamplerBuffer rg32ui over the run links */
#define OIT_TEXUNIT_IB_TRIANGLES 11    /* usamplerBuffer rgba32ui: the triangle table */
#define OIT_TEXUNIT_IB_RUN_WORDS 12    /* usamplerBuffer r32ui over the run core: word 4 slot + k */
#define OIT_TEXUNIT_IB_COMPONENTS 14   /* samplerBuffer rgba32f over the component table */
#define OIT_TEXUNIT_IB_NODES 15        /* usamplerBuffer rgba32ui over the nodes (fields) */
#define OIT_TEXUNIT_IB_TRIANGLE_REACH 19 /* samplerBuffer r32f: oit_model.triangle_reach */
/* coplanar clusters (oit_model.planes), bound by oit_gl_draw_scene */
#define OIT_TEXUNIT_TRIANGLE_PLANES 20 /* usamplerBuffer r32ui: each triangle's plane */
#define OIT_TEXUNIT_PLANES 21          /* samplerBuffer rgba32f: model-space planes (n, d) */
/* depth peeling in (depth, triangle) order (dp/peel.frag): the previous
 * layer's triangle (usampler2D, R32UI), written at colour location
 * OIT_DP_TIE_LOCATION of every peel framebuffer */
#define OIT_TEXUNIT_TIE_PREVIOUS 22
#define OIT_DP_TIE_LOCATION 2
#define OIT_SSBO_IB_TRIANGLES 13       /* the triangle table, written by ib/triangles.comp */
/* the tiles (OIT_IB_TILE_SIZE squared pixels) that hold fragments, one uint each
 * (x | y << 16, in tiles), appended by ib/sort.comp: the per-pixel passes of the
 * construction run over these instead of the whole image (ib/tiles.glsl) */
#define OIT_SSBO_IB_TILES 14
#define OIT_IB_TILE_SIZE 8
#define OIT_IB_TRIANGLE_BYTES 32       /* ids (3 uint) + component, eye-space plane (4 float) */
#define OIT_IB_NODE_BYTES 16
#define OIT_IB_RUN_CORE_BYTES 16
#define OIT_IB_RUN_LINKS_BYTES 8
/* ib counters (uint): [0..1] as OIT_FRAME_COUNTER_* ([2] unused: the non-empty
 * pixels are the histogram's bins 1.., which the sort counts for non-empty
 * pixels only; bin 0 is the C side's pixels - non-empty), then: */
#define OIT_IB_COUNTER_RUN_ALLOCATOR 3
#define OIT_IB_COUNTER_PSI_PIXELS 4
#define OIT_IB_COUNTER_FOUR_NEIGHBOURS 5
#define OIT_IB_COUNTER_LINKS 6
#define OIT_IB_COUNTER_SYMMETRIC_LINKS 7
#define OIT_IB_COUNTER_SAME_COMPONENT_LINKS 8
#define OIT_IB_COUNTER_MAX_DISTANCE 9  /* floatBitsToUint of the largest distance */
#define OIT_IB_COUNTER_HISTOGRAM 10    /* OIT_IB_HISTOGRAM_BINS bins */
#define OIT_IB_HISTOGRAM_BINS 65       /* = OIT_HISTOGRAM_BINS in oit.h */
/* fragments queued for the epsilon search (ib/neighbours_epsilon.comp) */
#define OIT_IB_COUNTER_EPSILON_ITEMS 75
/* its work-group counts (x, y, z) for glDispatchComputeIndirect, written by
 * ib/epsilon_dispatch.comp: only as many groups as there are items */
#define OIT_IB_COUNTER_EPSILON_DISPATCH 76
#define OIT_IB_ITEMS_PER_GROUP 64      /* local size of the per-item passes */
#define OIT_IB_MAX_GROUPS_X 65535      /* the dispatch limit every GL guarantees per axis */
/* high words (times the 32-bit counter wrapped) of 64-bit counts: the fill's
 * fragments (as OIT_LL_COUNTER_FRAGMENTS_WRAPS) and neighbour_stats' link
 * counts, which reach 4 per fragment */
#define OIT_IB_COUNTER_FRAGMENTS_WRAPS 79
#define OIT_IB_COUNTER_LINKS_WRAPS 80
#define OIT_IB_COUNTER_SYMMETRIC_LINKS_WRAPS 81
#define OIT_IB_COUNTER_SAME_COMPONENT_LINKS_WRAPS 82
/* the tile list's length, and its work-group counts (x, y, z) for
 * glDispatchComputeIndirect, written by ib/tiles_dispatch.comp */
#define OIT_IB_COUNTER_TILES 83
#define OIT_IB_COUNTER_TILE_DISPATCH 84
#define OIT_IB_COUNTER_COUNT 87
/* frames drawn in bands of rows (alg_ib.c): the pixels whose run is in the
 * histogram's open last bin, by length, one uint for each length up to
 * OIT_IB_MAX_RUN_LENGTH, counted by ib/sort.comp; with them the frame's
 * fragments and psi, summed over the bands, stay exact */
#define OIT_SSBO_IB_LONG_RUNS 15
#define OIT_IB_LONG_RUN_LENGTHS 65536
/* a neighbour slot without a neighbour */
#define OIT_IB_NO_NEIGHBOUR 65535
/* the longest run (a pixel's list) whose layers a 16-bit link addresses:
 * layers 0..65534, 65535 is OIT_IB_NO_NEIGHBOUR; a longer one is an error */
#define OIT_IB_MAX_RUN_LENGTH 65535
/* ib passes: the capacity of the fill pool (uint), the pass parameter (int:
 * ping-pong source copy, blur direction) */
#define OIT_UNIFORM_IB_POOL_CAPACITY 16
#define OIT_UNIFORM_IB_PASS 17
/* ib compute passes: the band of rows (ivec4): the rows stored [x, y), the rows
 * composed and counted [z, w); the whole image in a frame drawn whole */
#define OIT_UNIFORM_IB_BAND 18

/* ib modulation modes and views, the numbers of oit_modulation_mode and oit_view in oit.h */
#define OIT_IB_MODE_NONE 0
#define OIT_IB_MODE_CURVATURE 1
#define OIT_IB_MODE_DISTANCE 2
#define OIT_IB_MODE_DIST_CURV 3
#define OIT_IB_MODE_FIELDS 4
#define OIT_IB_MODE_EDGES 5
#define OIT_IB_VIEW_COLOUR 0
#define OIT_IB_VIEW_HEATMAP 1
#define OIT_IB_VIEW_PEEL_LIMIT 2
#define OIT_IB_VIEW_LAYER 3
#define OIT_IB_VIEW_NEIGHBOURS 4
#define OIT_IB_VIEW_CURVATURE 5
#define OIT_IB_VIEW_DISTANCE 6
#define OIT_IB_VIEW_FIELDS 7
/* ib neighbour searches (oit_neighbour_search) and distance modes (oit_distance_mode) */
#define OIT_IB_SEARCH_INDEX 1
#define OIT_IB_SEARCH_WELDED 2
#define OIT_IB_SEARCH_EPSILON 3
#define OIT_IB_DISTANCE_ADJACENT 0
#define OIT_IB_DISTANCE_SKIP 1
#define OIT_IB_DISTANCE_FAR_END 2

/* ---- multi-layer alpha blending (alg_mlab.c, shaders/mlab/mlab_layers.glsl) ----
 * Per pixel (x, y) of a W x H image, k = oit_algorithm_config.layers layers, front to
 * back, layer i at index (y * W + x) * k + i of OIT_SSBO_MLAB_LAYERS, one uvec4 each:
 *   x = packUnorm2x16(r, g), y = packUnorm2x16(b, t)   premultiplied colour and
 *                                                       transmittance t, 16 bit each
 *   z = floatBitsToUint(oit_canonical_depth())         depth key (a merged layer keeps
 *   w = gl_PrimitiveID                                 its nearer part's depth and triangle)
 * OIT_IMAGE_MLAB_COUNT (r32ui): the fragments the pixel received (its layers are the
 * first min(count, k)); OIT_IMAGE_MLAB_LOCK (r32ui): the pixel's spin lock, 0 free, 1
 * taken. Only the layers the count names are ever read, so the layers need no clear. */
#define OIT_MLAB_LAYER_BYTES 16
#define OIT_MLAB_COUNT_BYTES 4
#define OIT_MLAB_LOCK_BYTES 4
#define OIT_SSBO_MLAB_LAYERS 1
#define OIT_SSBO_MLAB_COUNTERS 4
#define OIT_IMAGE_MLAB_COUNT 2
#define OIT_IMAGE_MLAB_LOCK 3
/* resolve: the layers read through a buffer texture (usamplerBuffer rgba32ui) */
#define OIT_TEXUNIT_MLAB_LAYERS 24
/* mlab counters (uint, OIT_SSBO_MLAB_COUNTERS) */
#define OIT_MLAB_COUNTER_FRAGMENTS 0       /* insert: fragments with alpha > 0 */
#define OIT_MLAB_COUNTER_FRAGMENTS_WRAPS 1 /* insert: times that counter wrapped (high word) */
#define OIT_MLAB_COUNTER_GAVE_UP 2         /* insert: fragments that never took their lock */
#define OIT_MLAB_COUNTER_MAX_LIST 3        /* resolve: the largest per-pixel count */
#define OIT_MLAB_COUNTER_NONEMPTY_PIXELS 4 /* resolve: pixels with a count > 0 */
#define OIT_MLAB_COUNTER_RESOLVED 5        /* resolve: sum of the counts (mod 2^32) */
#define OIT_MLAB_COUNTER_COUNT 6
/* tries at a pixel's lock before a fragment gives up (counted, and the frame fails):
 * far below the 65535 iterations after which llvmpipe silently ends a shader loop */
#define OIT_MLAB_LOCK_TRIES 4096
/* insert and resolve: k, the layers per pixel (uint) */
#define OIT_UNIFORM_MLAB_LAYERS 16

#endif
