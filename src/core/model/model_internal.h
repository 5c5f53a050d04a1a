/* model_internal.h: what the model's files share; internal to the core.
 * The layers, each calling only the ones below it:
 *   oit_model_load (model_import.c): the file's checks, the warnings, the
 *     parts' names; it reads the file through
 *   the OBJ reader (model_obj.cpp), OpenCASCADE for STEP and IGES
 *     (model_occt.cpp, the only file that includes OCCT's headers) or Assimp
 *     (model_assimp.c, the only file that includes Assimp's importer), then calls
 *   oit_model_finish (model_finish.c): validation, centring, normals, the
 *     exact vertex join, welding, bounds, reach; and the coplanar planes
 *     (model_planes.c).
 * model_contained.c runs oit_model_load in a worker process; scene_gen.c
 * writes the OBJ test scenes of `oit gen`. */
#ifndef OIT_MODEL_INTERNAL_H
#define OIT_MODEL_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/stat.h>

#include "oit.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Every count in the model must fit the GL's signed 32-bit indices and
 * gl_PrimitiveID, so anything above 2^31 is rejected. */
#define OIT_MODEL_LIMIT ((uint64_t)1 << 31)

/* A file's name in messages: what follows the last '/' (all of a path ending
 * in '/'). In model_import.c; the scene generator names its files with it. */
const char *oit_path_basename(const char *path);

/* ----------------------------------------- the finishing (model_finish.c) */

/* The colour of a part whose file gives none. */
extern const float oit_model_default_colour[3];

/* malloc(count * size) that fails instead of overflowing; count 0 gives a
 * valid 1-byte block so that callers can treat NULL as out of memory. The
 * calloc likewise. */
void *oit_model_alloc_array(uint64_t count, size_t size);
void *oit_model_calloc_array(uint64_t count, size_t size);

/* Vertices equal bit for bit in position, normal, first texture coordinate
 * and owning component become one; the triangles are re-indexed (why: at
 * the definition). vertex_owner: per vertex, its component. Before
 * oit_model_finish, on the positions as read. */
oit_status oit_model_join_identical_vertices(oit_model *model, float *texture_coordinates,
                                             const uint32_t *vertex_owner, oit_error *err);

/* bounds_min/max over every vertex and the radius about the origin that
 * holds them all (rounded up); OIT_E_INPUT if the extent overflows a float.
 * oit_model_derive recomputes them for moved parts. */
oit_status oit_model_bounds_and_radius(oit_model *model, oit_error *err);

/* Longest edges (per component and the model's) and every triangle's reach
 * (oit_model.triangle_reach), from positions, indices, welded ids and the
 * components; oit_model_derive recomputes them after adding caps. */
oit_status oit_model_edge_reach(oit_model *model, oit_error *err);

/* oit_component.closed for every component, from indices and welded ids. */
oit_status oit_model_closed_parts(oit_model *model, oit_error *err);

/* The coplanar planes (model_planes.c): fills planes, plane_count and
 * triangle_plane from the finished positions, bounds, radius and origin. */
oit_status oit_model_find_planes(oit_model *model, oit_error *err);

/* ------------------------------------------- the import (model_import.c) */

/* The warnings of one import (lines that differ only in their numbers are
 * one warning with a count). */
typedef struct import_warnings import_warnings;
void oit_import_warn(import_warnings *w, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* The one line for an import that failed: why is the reader's own reason. */
oit_status oit_import_failure(const char *name, const char *why, long long file_size, oit_error *err);

/* The first checks of every import, also made before a worker is started
 * (model_contained.c): path names a regular file; its stat in info. */
oit_status oit_model_check_regular_file(const char *path, const char *name, struct stat *info,
                                        oit_error *err);

/* Unique component names: a hash set over the names given so far. For each
 * name it also remembers the next "#N" suffix to try, so many meshes with one
 * name do not make the search quadratic. */
typedef struct name_set {
    uint32_t *slots;       /* component index + 1; 0 = empty */
    uint32_t *next_suffix; /* per component */
    uint64_t mask;
} name_set;
bool oit_name_set_init(name_set *set, uint64_t count);
void oit_name_set_free(name_set *set);
/* Names component index: mesh name, else node name, else "component N", made
 * unique with "#2", "#3"... */
/* out (OIT_NAME_SIZE bytes) = base + "#suffix", base cut short to fit: the
 * one spelling of a repeated name, for parts and assembly nodes alike. */
void oit_name_suffixed(char *out, const char *base, uint32_t suffix);
void oit_component_name(oit_model *model, name_set *set, uint32_t index, const char *mesh_name,
                        const char *node_name, bool instanced);

/* Colour channels and opacity in [0, 1]; what is not finite takes the default. */
void oit_clamp_material(oit_component *comp);

/* ------------------------------------------ the Assimp reader (model_assimp.c) */

/* Reads path (any format but OBJ) into out, not yet finished; Assimp's log
 * lines go to warnings. any_normals: some mesh has normals (keep them and
 * compute only the missing). On failure, the one line naming the file. */
oit_status oit_model_read_assimp(const char *path, const char *name, long long file_size,
                                 import_warnings *warnings, oit_model *out, bool *any_normals,
                                 oit_error *err);

/* ------------------------------------- the B-rep reader (model_occt.cpp) */

/* The B-rep formats OpenCASCADE reads. */
typedef enum occt_format { OCCT_FORMAT_NONE = 0, OCCT_FORMAT_STEP, OCCT_FORMAT_IGES } occt_format;
/* By the name's extension (.step .stp .iges .igs, any case), else by a STEP
 * file's first bytes ("ISO-10303-21;"). */
occt_format oit_occt_format(const char *path, const char *name);
/* Reads a STEP or IGES file into out (positions in millimetres, the assembly
 * tree, names, colours, unit and tessellation figures), not yet finished;
 * normals are given. On failure, the one line naming the file. */
oit_status oit_model_read_occt(const char *path, const char *name, occt_format format,
                               const oit_import_options *options, import_warnings *warnings,
                               oit_model *out, oit_error *err);

#ifdef __cplusplus
}
#endif

#endif
