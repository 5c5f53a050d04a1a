/* model_obj.h: the OBJ reader (model_obj.cpp), used by model_import.c in place of
 * Assimp's OBJ importer. Internal to the core. */
#ifndef OIT_MODEL_OBJ_H
#define OIT_MODEL_OBJ_H

#include <stdbool.h>
#include <stdint.h>

#include "oit.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One mesh as Assimp's OBJ importer made it: a group or object, split where
 * the material changes. Its vertices are its triangles' corners, in order. */
typedef struct obj_mesh {
    char name[OIT_NAME_SIZE];        /* "" = none */
    char object_name[OIT_NAME_SIZE]; /* the node's name */
    float colour[3], opacity;        /* the material's diffuse colour and opacity */
    bool invented_material;          /* Assimp's "DefaultMaterial": the renderer's default applies */
    uint32_t first_vertex, vertex_count;
    uint32_t first_triangle, triangle_count;
    bool has_normals;
} obj_mesh;

typedef struct obj_data {
    float *positions, *normals, *texture_coordinates; /* 3 per vertex */
    uint32_t *indices;                                 /* 3 per triangle, model-wide */
    obj_mesh *meshes;
    uint64_t vertex_count, triangle_count, mesh_count;
} obj_data;

/* Reads path (and its material libraries). Warnings go to warn(user, text),
 * one line each, as Assimp's log would have said them. On failure, false and
 * why (without the file's name). */
bool obj_read(const char *path, obj_data *out, void (*warn)(void *user, const char *text), void *user,
              char *why, size_t why_size);
void obj_free(obj_data *data);

#ifdef __cplusplus
}
#endif

#endif
