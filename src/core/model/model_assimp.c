/* model_assimp.c: every format but OBJ read through Assimp: the scene's node
 * tree walked iteratively, each mesh a node instances one component, node
 * transforms applied, materials' colour and opacity, the named nodes kept as
 * the model's assembly tree; Assimp's log gathered as
 * warnings, and the files a model refers to read through a file system of
 * our own, so that a failing one is named. The model it makes is finished by
 * model_import.c. The only file of the core that includes Assimp's importer. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "model_internal.h"

/* ------------------------------------------------------------------ log */

/* Assimp's log lines are "Warn,  T0: text" and "Error, T0: text". Errors
 * that end the import come back as the import's error instead; the ones
 * logged on a successful import are repairs (e.g. OFF indices clamped). What
 * this renderer never reads (bones, animations, textures) is left out. */
static void assimp_log(const char *message, char *user)
{
    import_warnings *w = (import_warnings *)user;
    bool warn = strncmp(message, "Warn", 4) == 0, error = strncmp(message, "Error", 5) == 0;
    if (!warn && !error)
        return;
    const char *text = strstr(message, ": ");
    text = text ? text + 2 : message;
    static const char *const unread[] = {"bone", "Bone", "nimation", "exture",
                                         "No object detected to attach"};
    for (size_t i = 0; i < sizeof unread / sizeof unread[0]; ++i)
        if (strstr(text, unread[i]))
            return;
    char line[OIT_ERROR_MESSAGE_SIZE];
    snprintf(line, sizeof line, "%s", text);
    size_t length = strlen(line);
    while (length > 0 && (line[length - 1] == '\n' || line[length - 1] == '\r' || line[length - 1] == ' '))
        line[--length] = '\0';
    /* Assimp's OFF reader replaces an index past the end by the last vertex. */
    const char *repair = strstr(line, "OFF: Vertex index is out of range")
                             ? " (it drew the face with the last vertex instead)"
                             : "";
    oit_import_warn(w, "the importer reports: %s%s", line, repair);
}

/* -------------------------------------------------------------- loading */

typedef struct load_state {
    const struct aiScene *scene;
    oit_model *model;
    uint64_t vertex_count, triangle_count, component_count; /* counted, then filled */
    bool any_normals; /* some mesh has normals: keep them, compute only the missing */
    uint32_t *mesh_uses; /* per Assimp mesh: how many nodes instance it */
    uint32_t *vertex_owner; /* per vertex: the component that filled it */
    float *texture_coordinates; /* per vertex: the first UV(W) channel, or 0 */
    name_set *names;
    /* Per node visited (depth first, parents first): its parent's visit, the
     * components it holds and those in its subtree (pass 1); the assembly
     * node its contents hang under (pass 2). */
    size_t visit_count, visit_capacity;
    uint32_t *visit_parent, *visit_own, *visit_anchor;
    uint64_t *visit_subtree;
    uint32_t *node_depth; /* per assembly node, 1 at the top */
    bool root_may_be_node; /* glTF: the root can be the file's own node */
    bool visit_out_of_memory;
    bool bad_index; /* first face index outside its mesh, for the message */
    uint32_t bad_mesh_face, bad_mesh_index;
    char bad_mesh_name[OIT_NAME_SIZE];
} load_state;

static bool mesh_has_triangles(const struct aiMesh *mesh)
{
    return mesh && (mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) && mesh->mNumVertices > 0 &&
           mesh->mNumFaces > 0 && mesh->mVertices;
}

static uint32_t mesh_triangle_count(const struct aiMesh *mesh)
{
    uint32_t count = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f)
        if (mesh->mFaces[f].mNumIndices == 3)
            ++count;
    return count;
}

/* Row-major Assimp matrices: a1..a4 is the first row, translation in a4/b4/c4. */
static void transform_point(const struct aiMatrix4x4 *m, const struct aiVector3D *v, float out[3])
{
    out[0] = (float)(m->a1 * v->x + m->a2 * v->y + m->a3 * v->z + m->a4);
    out[1] = (float)(m->b1 * v->x + m->b2 * v->y + m->b3 * v->z + m->b4);
    out[2] = (float)(m->c1 * v->x + m->c2 * v->y + m->c3 * v->z + m->c4);
}

static void multiply(const struct aiMatrix4x4 *a, const struct aiMatrix4x4 *b,
                     struct aiMatrix4x4 *out)
{
    const ai_real *pa = &a->a1, *pb = &b->a1;
    ai_real r[16];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            ai_real s = 0;
            for (int k = 0; k < 4; ++k)
                s += pa[i * 4 + k] * pb[k * 4 + j];
            r[i * 4 + j] = s;
        }
    memcpy(&out->a1, r, sizeof r);
}

/* Normals go through the cofactor matrix (inverse transpose up to scale). */
static void normal_matrix(const struct aiMatrix4x4 *m, double n[9], double *determinant)
{
    double a = m->a1, b = m->a2, c = m->a3, d = m->b1, e = m->b2, f = m->b3, g = m->c1,
           h = m->c2, i = m->c3;
    n[0] = e * i - f * h; n[1] = f * g - d * i; n[2] = d * h - e * g;
    n[3] = c * h - b * i; n[4] = a * i - c * g; n[5] = b * g - a * h;
    n[6] = b * f - c * e; n[7] = c * d - a * f; n[8] = a * e - b * d;
    *determinant = a * n[0] + b * n[1] + c * n[2];
}

/* The node tree is walked depth first, children in order, with a stack of
 * its own: files nest nodes as deep as they like (a glTF chain of 5,000
 * nodes is valid), and a recursion would either cut them off or overflow
 * the C stack. Each entry carries its node's global transform. */
typedef struct node_entry {
    const struct aiNode *node;
    struct aiMatrix4x4 global;
    uint32_t visit, parent_visit; /* the order of the visits (UINT32_MAX: the root's parent) */
} node_entry;

typedef struct node_walk {
    node_entry *entries;
    size_t count, capacity;
    uint32_t visits;
    bool out_of_memory;
} node_walk;

static void walk_push(node_walk *walk, const struct aiNode *node, const struct aiMatrix4x4 *global,
                      uint32_t parent_visit)
{
    if (!node || walk->out_of_memory)
        return;
    if (walk->count == walk->capacity) {
        size_t capacity = walk->capacity ? walk->capacity * 2 : 64;
        node_entry *grown = realloc(walk->entries, capacity * sizeof *grown);
        if (!grown) {
            walk->out_of_memory = true;
            return;
        }
        walk->entries = grown;
        walk->capacity = capacity;
    }
    walk->entries[walk->count].node = node;
    walk->entries[walk->count].global = *global;
    walk->entries[walk->count].parent_visit = parent_visit;
    ++walk->count;
}

/* Pops the next node in depth-first order and pushes its children; false
 * when the walk is over (or out of memory: walk->out_of_memory). */
static bool walk_next(node_walk *walk, node_entry *out)
{
    if (walk->visits == UINT32_MAX)
        walk->out_of_memory = true; /* no scene holds 2^32 nodes */
    if (walk->count == 0 || walk->out_of_memory)
        return false;
    *out = walk->entries[--walk->count];
    out->visit = walk->visits++;
    for (unsigned i = out->node->mNumChildren; i-- > 0;) {
        const struct aiNode *child = out->node->mChildren[i];
        if (!child)
            continue;
        struct aiMatrix4x4 global;
        multiply(&out->global, &child->mTransformation, &global);
        walk_push(walk, child, &global, out->visit);
    }
    return true;
}

/* Pass 1: count what one node instantiates (a mesh used by two nodes
 * becomes two components), and remember the visit for the tree. */
static void count_node(load_state *st, const node_entry *entry)
{
    const struct aiNode *node = entry->node;
    if (st->visit_count == st->visit_capacity) {
        size_t capacity = st->visit_capacity ? st->visit_capacity * 2 : 64;
        uint32_t *parent = realloc(st->visit_parent, capacity * sizeof *parent);
        if (parent)
            st->visit_parent = parent;
        uint32_t *own = realloc(st->visit_own, capacity * sizeof *own);
        if (own)
            st->visit_own = own;
        if (!parent || !own) {
            st->visit_out_of_memory = true;
            return;
        }
        st->visit_capacity = capacity;
    }
    const uint64_t components_before = st->component_count;
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
        unsigned m = node->mMeshes[i];
        if (m >= st->scene->mNumMeshes)
            continue;
        const struct aiMesh *mesh = st->scene->mMeshes[m];
        if (!mesh_has_triangles(mesh))
            continue;
        uint32_t triangles = mesh_triangle_count(mesh);
        if (triangles == 0)
            continue;
        if (st->mesh_uses[m] < UINT32_MAX)
            ++st->mesh_uses[m];
        st->vertex_count += mesh->mNumVertices;
        st->triangle_count += triangles;
        st->component_count += 1;
        st->any_normals |= mesh->mNormals != NULL;
    }
    st->visit_parent[st->visit_count] = entry->parent_visit;
    st->visit_own[st->visit_count] = (uint32_t)(st->component_count - components_before);
    ++st->visit_count;
}

static void material_properties(const struct aiScene *scene, unsigned index, oit_component *comp)
{
    memcpy(comp->colour, oit_model_default_colour, sizeof comp->colour);
    comp->opacity = 1.0f;
    if (index >= scene->mNumMaterials)
        return;
    const struct aiMaterial *mat = scene->mMaterials[index];
    struct aiString name;
    /* For files without materials Assimp invents one: "DefaultMaterial"
     * (STL, OBJ), or an unnamed one (PLY white, OFF grey 0.6). Our default
     * applies to those. (A glTF base colour is always the file's own.) */
    bool invented = aiGetMaterialString(mat, AI_MATKEY_NAME, &name) != aiReturn_SUCCESS ||
                    strcmp(name.data, AI_DEFAULT_MATERIAL_NAME) == 0;
    struct aiColor4D colour;
    bool have_base = false;
    /* glTF (metallic-roughness) base colour wins; its alpha is the opacity. */
    if (aiGetMaterialColor(mat, AI_MATKEY_BASE_COLOR, &colour) == aiReturn_SUCCESS) {
        have_base = true;
        comp->colour[0] = colour.r;
        comp->colour[1] = colour.g;
        comp->colour[2] = colour.b;
        comp->opacity = colour.a;
    } else if (invented) {
        return;
    } else if (aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &colour) == aiReturn_SUCCESS) {
        comp->colour[0] = colour.r;
        comp->colour[1] = colour.g;
        comp->colour[2] = colour.b;
    }
    /* MTL d / Tr and most formats: the opacity property. glTF importers set
     * it to the base alpha as well; take the smaller where both exist. */
    ai_real opacity;
    unsigned max = 1;
    if (aiGetMaterialFloatArray(mat, AI_MATKEY_OPACITY, &opacity, &max) == aiReturn_SUCCESS)
        comp->opacity = have_base ? fminf(comp->opacity, (float)opacity) : (float)opacity;
    oit_clamp_material(comp);
}

/* ---------------------------------------------------------- the assembly tree */

/* The assembly tree (oit_model.nodes; docs/cli.md, "Assemblies") is Assimp's
 * node hierarchy with only the nodes someone looking for a part needs:
 * - a node is kept when it has a name of the file's own and a part in it or
 *   below it. Nodes without a name and the ones Assimp invents (glTF's
 *   "nodes[3]", FBX's pivot helpers "..._$AssimpFbx$_...", roots like
 *   "<3DSRoot>", "$dummy_root", FBX's "RootNode", glTF's "ROOT") hand their
 *   contents to their parent;
 * - the root is kept only when it is the file's own and holds no mesh itself
 *   (a glTF scene of one node "gearbox"); STL, PLY and OFF put their meshes
 *   in the root and so keep no tree (component_node NULL);
 * - a node holding one part and nothing below it, the part named after it,
 *   is that part (gearbox/bolt_1, not gearbox/bolt_1/bolt_1); a part named
 *   otherwise (a mesh name) stays under its node (gearbox/shaft/Cylinder.001);
 * - at most ASSIMP_TREE_DEPTH levels: the parts of deeper nodes hang under the
 *   deepest kept one (a hostile file nests nodes 100,000 deep).
 * Components keep the names and the order they have without a tree; a node
 * whose name a sibling (node or part) has already gets "#2", "#3"... */
#define ASSIMP_TREE_DEPTH 32

static bool invented_node_name(const struct aiNode *node, bool root)
{
    const char *name = node->mName.data;
    const char *end = memchr(name, '\0', sizeof node->mName.data);
    if (!end || end == name)
        return true;
    size_t length = (size_t)(end - name);
    if (strncmp(name, "nodes[", 6) == 0 || strstr(name, "$AssimpFbx$") || name[0] == '$' ||
        (name[0] == '<' && name[length - 1] == '>'))
        return true;
    return root && (strcmp(name, "RootNode") == 0 || strcmp(name, "ROOT") == 0);
}

/* A node's name as a part's is made (control characters replaced, cut to fit). */
static void copy_node_name(char *out, const char *in)
{
    size_t i = 0;
    for (; in[i] && i + 1 < OIT_NAME_SIZE; ++i)
        out[i] = (unsigned char)in[i] < 0x20 ? '_' : in[i];
    out[i] = '\0';
}

/* The part took the node's name, maybe with a "#N" of the unique-name rule
 * (which cuts a long name short to fit). */
static bool named_after(const char *part, const char *node)
{
    if (strcmp(part, node) == 0)
        return true;
    const char *hash = strrchr(part, '#');
    if (!hash || hash == part || !hash[1] || strspn(hash + 1, "0123456789") != strlen(hash + 1))
        return false;
    size_t base = (size_t)(hash - part);
    return strncmp(part, node, base) == 0 && (node[base] == '\0' || strlen(part) == OIT_NAME_SIZE - 1);
}

/* Pass 2, after a node's components are made: is it a node of the tree? */
static void place_node(load_state *st, const node_entry *entry, uint32_t first_component)
{
    oit_model *model = st->model;
    const uint32_t v = entry->visit;
    const bool root = entry->parent_visit == UINT32_MAX;
    uint32_t parent = OIT_NO_NODE;
    if (!root && entry->parent_visit < st->visit_count)
        parent = st->visit_anchor[entry->parent_visit];
    for (uint32_t c = first_component; c < model->component_count; ++c)
        model->component_node[c] = parent;
    if (v >= st->visit_count)
        return; /* (the walks visit the same nodes) */
    st->visit_anchor[v] = parent;
    if (st->visit_subtree[v] == 0 || invented_node_name(entry->node, root) ||
        (root && (!st->root_may_be_node || st->visit_own[v] > 0)))
        return;
    if (parent != OIT_NO_NODE && st->node_depth[parent] >= ASSIMP_TREE_DEPTH)
        return;
    char name[OIT_NAME_SIZE];
    copy_node_name(name, entry->node->mName.data);
    if (st->visit_own[v] == 1 && st->visit_subtree[v] == 1 && first_component < model->component_count &&
        named_after(model->components[first_component].name, name))
        return;
    const uint32_t n = model->node_count++;
    memcpy(model->nodes[n].name, name, sizeof name);
    model->nodes[n].parent = parent;
    st->node_depth[n] = parent == OIT_NO_NODE ? 1 : st->node_depth[parent] + 1;
    st->visit_anchor[v] = n;
    for (uint32_t c = first_component; c < model->component_count; ++c)
        model->component_node[c] = n;
}

/* Names unique among siblings: a hash set over (parent, name) of the parts
 * (unique already: their names are unique in the model) and the nodes, in
 * order. Entry i < component_count is a part, the others nodes. Like
 * name_set, each entry remembers the next "#N" to try. */
typedef struct sibling_names {
    const oit_model *model;
    uint32_t *slots; /* entry + 1; 0 = empty */
    uint32_t *next_suffix;
    uint64_t mask;
} sibling_names;

static void sibling_key(const sibling_names *set, uint32_t entry, uint32_t *parent, const char **name)
{
    const oit_model *m = set->model;
    if (entry < m->component_count) {
        *parent = m->component_node[entry];
        *name = m->components[entry].name;
    } else {
        *parent = m->nodes[entry - m->component_count].parent;
        *name = m->nodes[entry - m->component_count].name;
    }
}

static uint64_t sibling_slot(const sibling_names *set, uint32_t parent, const char *name)
{
    uint64_t h = 0xcbf29ce484222325ull; /* FNV-1a over the parent, then the name */
    for (int k = 0; k < 4; ++k) {
        h ^= (parent >> (8 * k)) & 0xffu;
        h *= 0x100000001b3ull;
    }
    for (const char *c = name; *c; ++c) {
        h ^= (unsigned char)*c;
        h *= 0x100000001b3ull;
    }
    for (uint64_t slot = h & set->mask;; slot = (slot + 1) & set->mask) {
        if (!set->slots[slot])
            return slot;
        uint32_t other_parent;
        const char *other_name;
        sibling_key(set, set->slots[slot] - 1, &other_parent, &other_name);
        if (other_parent == parent && strcmp(other_name, name) == 0)
            return slot;
    }
}

static bool unique_sibling_names(oit_model *model)
{
    const uint64_t entries = (uint64_t)model->component_count + model->node_count;
    uint64_t capacity = 16;
    while (capacity < entries * 2)
        capacity *= 2;
    sibling_names set = {.model = model, .mask = capacity - 1};
    set.slots = oit_model_calloc_array(capacity, sizeof *set.slots);
    set.next_suffix = oit_model_alloc_array(entries, sizeof *set.next_suffix);
    bool ok = set.slots && set.next_suffix;
    for (uint64_t e = 0; ok && e < entries; ++e) {
        uint32_t parent;
        const char *name;
        sibling_key(&set, (uint32_t)e, &parent, &name);
        set.next_suffix[e] = 2;
        uint64_t slot = sibling_slot(&set, parent, name);
        if (set.slots[slot] && e >= model->component_count) {
            char *out = model->nodes[e - model->component_count].name;
            char base[OIT_NAME_SIZE];
            memcpy(base, out, sizeof base);
            const uint32_t owner = set.slots[slot] - 1;
            for (uint32_t suffix = set.next_suffix[owner];; ++suffix) {
                oit_name_suffixed(out, base, suffix);
                slot = sibling_slot(&set, parent, out);
                if (!set.slots[slot]) {
                    set.next_suffix[owner] = suffix + 1;
                    break;
                }
            }
        }
        set.slots[slot] = (uint32_t)e + 1; /* (two parts with one name: cannot be, they are unique) */
    }
    free(set.slots);
    free(set.next_suffix);
    return ok;
}

/* After pass 1: each visit's subtree count, and room for the tree. */
static bool prepare_tree(load_state *st)
{
    oit_model *model = st->model;
    st->visit_subtree = oit_model_alloc_array(st->visit_count, sizeof *st->visit_subtree);
    st->visit_anchor = oit_model_alloc_array(st->visit_count, sizeof *st->visit_anchor);
    if (!st->visit_subtree || !st->visit_anchor)
        return false;
    for (size_t v = 0; v < st->visit_count; ++v)
        st->visit_subtree[v] = st->visit_own[v];
    uint64_t candidates = 0;
    for (size_t v = st->visit_count; v-- > 0;) {
        if (v > 0 && st->visit_parent[v] < v)
            st->visit_subtree[st->visit_parent[v]] += st->visit_subtree[v];
        candidates += st->visit_subtree[v] > 0;
    }
    model->nodes = oit_model_calloc_array(candidates, sizeof *model->nodes);
    st->node_depth = oit_model_alloc_array(candidates, sizeof *st->node_depth);
    model->component_node = oit_model_alloc_array(st->component_count, sizeof *model->component_node);
    return model->nodes && st->node_depth && model->component_node;
}

/* After pass 2: no tree when no node was kept; names unique among siblings. */
static bool finish_tree(oit_model *model)
{
    if (model->node_count == 0) {
        free(model->nodes);
        free(model->component_node);
        model->nodes = NULL;
        model->component_node = NULL;
        return true;
    }
    oit_model_node *fitted = realloc(model->nodes, (size_t)model->node_count * sizeof *fitted);
    if (fitted)
        model->nodes = fitted;
    return unique_sibling_names(model);
}

/* Pass 2: copy one node's vertices (transformed to model space), triangles,
 * components; then place it in the assembly tree. */
static void fill_node(load_state *st, const node_entry *entry)
{
    const struct aiNode *node = entry->node;
    struct aiMatrix4x4 global = entry->global;
    const uint32_t first_component = st->model->component_count;
    double nm[9], determinant;
    normal_matrix(&global, nm, &determinant);
    oit_model *model = st->model;
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
        unsigned m = node->mMeshes[i];
        if (m >= st->scene->mNumMeshes)
            continue;
        const struct aiMesh *mesh = st->scene->mMeshes[m];
        if (!mesh_has_triangles(mesh) || mesh_triangle_count(mesh) == 0)
            continue;
        uint32_t c = model->component_count++;
        oit_component *comp = &model->components[c];
        oit_component_name(model, st->names, c, mesh->mName.length > 0 ? mesh->mName.data : "",
                       node->mName.length > 0 ? node->mName.data : "", st->mesh_uses[m] > 1);
        material_properties(st->scene, mesh->mMaterialIndex, comp);
        comp->first_triangle = model->triangle_count;

        uint32_t base = model->vertex_count;
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            float *p = model->positions + ((size_t)base + v) * 3;
            transform_point(&global, &mesh->mVertices[v], p);
            float *n = model->normals + ((size_t)base + v) * 3;
            if (mesh->mNormals) {
                const struct aiVector3D *in = &mesh->mNormals[v];
                for (int k = 0; k < 3; ++k)
                    n[k] = (float)(nm[k * 3] * in->x + nm[k * 3 + 1] * in->y + nm[k * 3 + 2] * in->z);
            } else {
                n[0] = n[1] = n[2] = 0.0f; /* recomputed by oit_model_finish */
            }
        }
        model->vertex_count += mesh->mNumVertices;

        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const struct aiFace *face = &mesh->mFaces[f];
            if (face->mNumIndices != 3)
                continue; /* a stray point or line SortByPType left behind */
            uint32_t *tri = model->indices + (size_t)model->triangle_count * 3;
            for (int k = 0; k < 3; ++k) {
                /* Out-of-range indices stay out of range (finish reports them). */
                if (face->mIndices[k] >= mesh->mNumVertices && !st->bad_index) {
                    st->bad_index = true;
                    st->bad_mesh_face = f;
                    st->bad_mesh_index = face->mIndices[k];
                    snprintf(st->bad_mesh_name, sizeof st->bad_mesh_name, "%s", comp->name);
                }
                uint64_t index = (uint64_t)base + face->mIndices[k];
                tri[k] = index >= model->vertex_count ? UINT32_MAX : (uint32_t)index;
            }
            if (determinant < 0.0) { /* a mirroring transform flips the winding back */
                uint32_t t = tri[1];
                tri[1] = tri[2];
                tri[2] = t;
            }
            ++model->triangle_count;
        }
        comp->triangle_count = model->triangle_count - comp->first_triangle;
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            st->vertex_owner[base + v] = c;
            float *uv = st->texture_coordinates + ((size_t)base + v) * 3;
            const struct aiVector3D *in = mesh->mTextureCoords[0] ? &mesh->mTextureCoords[0][v] : NULL;
            uv[0] = in ? (float)in->x : 0.0f;
            uv[1] = in ? (float)in->y : 0.0f;
            uv[2] = in ? (float)in->z : 0.0f;
        }
    }
    place_node(st, entry, first_component);
}

/* Runs visit on every node of the scene, depth first; false when out of memory. */
static bool walk_scene(load_state *st, void (*visit)(load_state *, const node_entry *))
{
    /* The root node's transform is applied too: importers put axis
     * conversions (e.g. Z-up to Y-up) there. */
    node_walk walk = {0};
    walk_push(&walk, st->scene->mRootNode, &st->scene->mRootNode->mTransformation, UINT32_MAX);
    node_entry entry;
    while (walk_next(&walk, &entry))
        visit(st, &entry);
    bool ok = !walk.out_of_memory && !st->visit_out_of_memory;
    free(walk.entries);
    return ok;
}

/* ------------------------------------------------- files the model refers to */

/* Assimp reads through this file system so that the files a model refers to
 * (an OBJ's material libraries, a glTF's buffers) are known: when an import
 * fails, it is tried once more with those files refused, and if the error
 * goes away (or changes) the message names the referred file, not the
 * model. */
typedef struct import_files {
    const char *model_path;
    bool refuse_others;
    char first_other[4096]; /* the first other file opened, "" if none */
    char not_regular[OIT_ERROR_MESSAGE_SIZE]; /* "NAME: not a regular file (a FIFO)" for the first such, or "" */
} import_files;

static FILE *io_stream(struct aiFile *file) { return (FILE *)(void *)file->UserData; }

static size_t io_read(struct aiFile *file, char *buffer, size_t size, size_t count)
{
    return fread(buffer, size, count, io_stream(file));
}

static size_t io_write(struct aiFile *file, const char *buffer, size_t size, size_t count)
{
    (void)file, (void)buffer, (void)size, (void)count;
    return 0; /* import only */
}

static size_t io_tell(struct aiFile *file)
{
    long position = ftell(io_stream(file));
    return position < 0 ? 0 : (size_t)position;
}

static size_t io_size(struct aiFile *file)
{
    FILE *stream = io_stream(file);
    long position = ftell(stream), end = -1;
    if (position >= 0 && fseek(stream, 0, SEEK_END) == 0)
        end = ftell(stream);
    if (position >= 0)
        fseek(stream, position, SEEK_SET);
    return end < 0 ? 0 : (size_t)end;
}

static void io_flush(struct aiFile *file) { fflush(io_stream(file)); }

static enum aiReturn io_seek(struct aiFile *file, size_t offset, enum aiOrigin origin)
{
    int whence = origin == aiOrigin_SET ? SEEK_SET : origin == aiOrigin_CUR ? SEEK_CUR : SEEK_END;
    /* aiOrigin_CUR moves backwards by a wrapped-around size_t */
    return fseek(io_stream(file), (long)offset, whence) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
}

static struct aiFile *io_open(struct aiFileIO *io, const char *path, const char *mode)
{
    import_files *files = (import_files *)(void *)io->UserData;
    if (strcmp(path, files->model_path) != 0) {
        if (!files->first_other[0])
            snprintf(files->first_other, sizeof files->first_other, "%s", path);
        if (files->refuse_others)
            return NULL;
    }
    struct aiFile *file = calloc(1, sizeof *file);
    /* a file the model refers to (a glTF's .bin) must be a regular file too:
     * a FIFO would block the import until the wall limit */
    FILE *stream = NULL;
    oit_error refused;
    if (file && mode[0] == 'r' && oit_open_regular_file(path, NULL, &stream, &refused) != OIT_OK) {
        const char *kind = strstr(refused.message, "not a regular file");
        if (kind && !files->not_regular[0])
            snprintf(files->not_regular, sizeof files->not_regular, "%.200s: %s", oit_path_basename(path), kind);
    } else if (file && mode[0] != 'r') {
        stream = fopen(path, mode);
    }
    if (!stream) {
        free(file);
        return NULL;
    }
    file->ReadProc = io_read;
    file->WriteProc = io_write;
    file->TellProc = io_tell;
    file->FileSizeProc = io_size;
    file->SeekProc = io_seek;
    file->FlushProc = io_flush;
    file->UserData = (aiUserData)(void *)stream;
    return file;
}

static void io_close(struct aiFileIO *io, struct aiFile *file)
{
    (void)io;
    if (file) {
        fclose(io_stream(file));
        free(file);
    }
}

static const struct aiScene *import_with(const char *path, unsigned flags,
                                         const struct aiPropertyStore *props, import_files *files)
{
    struct aiFileIO io = {io_open, io_close, (aiUserData)(void *)files};
    return aiImportFileExWithProperties(path, flags, &io, props);
}

/* After a failed import that opened other files: was it one of those? */
static void name_failing_file(const char *path, unsigned flags,
                              const struct aiPropertyStore *props, import_files *files,
                              char *why, size_t why_size)
{
    if (!files->first_other[0])
        return;
    char other[4096];
    snprintf(other, sizeof other, "%s", files->first_other);
    files->refuse_others = true;
    const struct aiScene *again = import_with(path, flags, props, files);
    const char *again_why = again ? "" : aiGetErrorString();
    bool theirs = again || !again_why || strcmp(again_why, why) != 0;
    if (again)
        aiReleaseImport(again);
    if (!theirs)
        return;
    const char *other_name = oit_path_basename(other);
    const char *dot = strrchr(other_name, '.');
    char reason[OIT_ERROR_MESSAGE_SIZE];
    snprintf(reason, sizeof reason, "%s", why);
    snprintf(why, why_size, "%s %.200s: %.280s",
             dot && strcasecmp(dot, ".mtl") == 0 ? "material library" : "the file it refers to,",
             other_name, reason);
}

oit_status oit_model_read_assimp(const char *path, const char *name, long long file_size,
                                 import_warnings *warnings, oit_model *out, bool *any_normals,
                                 oit_error *err)
{
    /* Post-processing, and why:
     * - Triangulate: polygons become triangles (the renderer draws triangles).
     * - SortByPType + SBP_REMOVE(points, lines): a mesh mixing primitive types
     *   is split and the point and line meshes dropped, so OBJ line/point
     *   elements never reach us and a file with nothing else has no triangles.
     * - ValidateDataStructure: Assimp rejects broken index data itself.
     * Not used: JoinIdenticalVertices (OBJ and STL give one vertex per face
     *   corner; oit_model_join_identical_vertices shares them exactly, where Assimp's
     *   join uses tolerances that depend on the model's units),
     *   PreTransformVertices (it merges meshes sharing a material and
     *   loses their names; the node tree is walked here instead, applying
     *   node transforms), FindDegenerates (it would turn zero-area triangles
     *   into lines or points and change the triangle count; they are harmless),
     *   GenNormals (missing normals are computed in oit_model_finish). */
    unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure;
    struct aiPropertyStore *props = aiCreatePropertyStore();
    if (!props)
        return oit_fail(err, OIT_E_RUNTIME, "%s: out of memory", name);
    aiSetImportPropertyInteger(props, AI_CONFIG_PP_SBP_REMOVE,
                               aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    /* Assimp's log is process-wide: one import at a time listens to it (and
     * nothing of it reaches stderr). */
    static pthread_mutex_t import_lock = PTHREAD_MUTEX_INITIALIZER;
    pthread_mutex_lock(&import_lock);
    struct aiLogStream log = {assimp_log, (char *)warnings};
    aiAttachLogStream(&log);
    import_files files = {.model_path = path};
    const struct aiScene *scene = import_with(path, flags, props, &files);
    char why_text[OIT_ERROR_MESSAGE_SIZE] = "";
    if (!scene) {
        const char *assimp_why = aiGetErrorString();
        snprintf(why_text, sizeof why_text, "%s", assimp_why ? assimp_why : "");
        if (files.not_regular[0])
            snprintf(why_text, sizeof why_text, "the file it refers to, %.480s", files.not_regular);
        else if (why_text[0])
            name_failing_file(path, flags, props, &files, why_text, sizeof why_text);
    }
    aiDetachLogStream(&log);
    pthread_mutex_unlock(&import_lock);
    aiReleasePropertyStore(props);
    if (!scene)
        return oit_import_failure(name, why_text, file_size, err);
    if (!scene->mRootNode) {
        aiReleaseImport(scene);
        return oit_fail(err, OIT_E_INPUT, "%s: no triangles (the file has no scene nodes)", name);
    }

    oit_status status = OIT_OK;
    const char *extension = strrchr(name, '.');
    load_state st = {.scene = scene, .model = out,
                     .root_may_be_node = extension && (strcasecmp(extension, ".gltf") == 0 ||
                                                       strcasecmp(extension, ".glb") == 0)};
    name_set names = {0};
    st.names = &names;
    st.mesh_uses = oit_model_calloc_array(scene->mNumMeshes, sizeof *st.mesh_uses);
    if (!st.mesh_uses) {
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory", name);
        goto done;
    }
    if (!walk_scene(&st, count_node)) {
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory walking the node tree", name);
        goto done;
    }
    if (st.triangle_count == 0) {
        status = oit_fail(err, OIT_E_INPUT, "%s: no triangles", name);
        goto done;
    }
    if (st.vertex_count > OIT_MODEL_LIMIT || st.triangle_count > OIT_MODEL_LIMIT ||
        st.component_count > OIT_MODEL_LIMIT) {
        status = oit_fail(err, OIT_E_INPUT,
                          "%s: too large: %llu vertices, %llu triangles, %llu components "
                          "(limit 2^31)",
                          name, (unsigned long long)st.vertex_count,
                          (unsigned long long)st.triangle_count,
                          (unsigned long long)st.component_count);
        goto done;
    }
    out->positions = oit_model_alloc_array(st.vertex_count * 3, sizeof *out->positions);
    out->normals = oit_model_alloc_array(st.vertex_count * 3, sizeof *out->normals);
    out->indices = oit_model_alloc_array(st.triangle_count * 3, sizeof *out->indices);
    out->components = oit_model_calloc_array(st.component_count, sizeof *out->components);
    st.vertex_owner = oit_model_alloc_array(st.vertex_count, sizeof *st.vertex_owner);
    st.texture_coordinates = oit_model_alloc_array(st.vertex_count * 3, sizeof *st.texture_coordinates);
    if (!out->positions || !out->normals || !out->indices || !out->components || !st.vertex_owner ||
        !st.texture_coordinates ||
        !oit_name_set_init(&names, st.component_count)) {
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory for %llu vertices", name,
                          (unsigned long long)st.vertex_count);
        goto done;
    }
    if (!prepare_tree(&st)) {
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory for the assembly tree", name);
        goto done;
    }
    if (!walk_scene(&st, fill_node))
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory walking the node tree", name);
    else if (!finish_tree(out))
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory for the assembly tree", name);
    else if (st.bad_index)
        status = oit_fail(err, OIT_E_INPUT,
                          "%s: face %u of mesh '%s' refers to vertex %u, outside the mesh", name,
                          st.bad_mesh_face, st.bad_mesh_name, st.bad_mesh_index);
    else
        status = oit_model_join_identical_vertices(out, st.texture_coordinates, st.vertex_owner, err);

done:
    aiReleaseImport(scene);
    free(st.mesh_uses);
    free(st.vertex_owner);
    free(st.texture_coordinates);
    free(st.visit_parent);
    free(st.visit_own);
    free(st.visit_subtree);
    free(st.visit_anchor);
    free(st.node_depth);
    oit_name_set_free(&names);
    *any_normals = st.any_normals;
    return status;
}

