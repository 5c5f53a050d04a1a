/*
 * model_planes.c: the coplanar planes of a model (oit_model.planes), which
 * give every exact algorithm and the reference one sort depth for faces that
 * coincide (docs/algorithms.md, "Ties and precision").
 *
 * A plane cluster is a set of triangles whose vertices all lie within the
 * tolerance of one plane, the plane of its largest triangle (its seed). A
 * triangle finds the clusters that may hold it in one of two ways:
 * - by its plane: clusters are hashed by their normal (steps of 1/256 per
 *   component) and offset (steps of 1024 tolerances), and a triangle whose
 *   normal is certain to that resolution looks in its bucket, the nearer
 *   neighbours in normal, and as many offset steps as its normal's
 *   uncertainty times its distance from the origin spans (at most
 *   PLANE_OFFSET_PROBES_MAX). Most triangles at the origin are such;
 *   far-apart faces in one plane then share a cluster;
 * - by where it is: a triangle's normal is only as good as its vertices. In
 *   a model far from the origin, float positions carry few bits for the
 *   part's own size, and a small triangle's normal can be off by degrees
 *   while every vertex still lies on the plane within the tolerance. Such a
 *   triangle looks for the clusters of the triangles near it in a loose
 *   grid, which does not depend on its normal.
 * Clusters of one plane that start apart (seeds far from each other, then a
 * triangle that both accept) are merged when every vertex of one lies on the
 * other's plane, so the result does not depend on which came first.
 *
 * Clustering only decides ties: coplanar faces that never overlap (far apart
 * in one plane) may stay separate clusters, and nothing in the image changes.
 *
 * The grid (built only when some triangle needs it): a triangle's level is
 * the smallest whose cells are at least twice
 * its bounding box (expanded by the tolerance); its cluster is listed in the
 * cell holding its box centre at that level ("own"), and at every coarser
 * level that some triangle has ("below"). Two triangles whose expanded boxes
 * overlap then always meet: the later one looks at the 2x2x2 cells nearest
 * its box centre, at its own level and every coarser one (own entries), and
 * at its own level for the finer ones (below entries).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model_internal.h"

/* Cells of level 0 are 4 tolerances wide, so even a triangle of no extent
 * (its box is 2 tolerances wide once expanded) has a level. */
#define PLANE_GRID_LEVELS 48

/* The plane hash's steps: normals in 1/256 per component, offsets in 1024
 * tolerances, both far coarser than the rounding of a triangle whose plane is
 * certain enough to be looked up by it (plane_uncertainty). */
#define PLANE_NORMAL_STEPS 256.0
#define PLANE_OFFSET_STEPS 1024.0
#define PLANE_OFFSET_PROBES_MAX 16
/* A search that has listed this many clusters stops: only a pathological
 * model (tens of thousands of tiny triangles stacked in one place, far from
 * the origin) gets there, and it is better to split a tie than to hang. */
#define PLANE_CANDIDATES_MAX 4096

typedef struct plane_cluster {
    double normal[3], d; /* the seed's plane: n . p + d = 0, relative coordinates */
    int32_t key[4];      /* its bucket in the plane hash */
    uint32_t next;       /* the next cluster in the same hash chain + 1, 0 = none */
    double seed_area;    /* twice the seed's area: the larger seed's plane wins a merge */
    uint32_t parent;     /* union-find: itself when a root */
    uint32_t first, last; /* member triangles, linked through member_next */
    uint32_t size;
    uint32_t failed_with, failed_size; /* the last merge into this root that was refused */
    uint32_t stamp;      /* the triangle whose search last listed this root */
} plane_cluster;

typedef struct grid_cell {
    int32_t key[4];      /* level, x, y, z */
    uint32_t own, below; /* entry chains + 1, 0 = none */
    uint32_t last_own, last_below; /* the cluster most recently put in each, + 1 */
} grid_cell;

typedef struct grid_entry {
    uint32_t cluster;
    uint32_t next; /* + 1, 0 = end */
} grid_entry;

typedef struct plane_grid {
    grid_cell *cells;
    uint32_t cell_count, cell_capacity;
    uint32_t *slots; /* open addressing: cell index + 1 */
    uint64_t slot_mask;
    grid_entry *entries;
    uint64_t entry_count, entry_capacity;
    double base[3];  /* the grid's corner: the model's box minimum */
    double cell0;    /* the width of a level-0 cell */
    uint64_t levels_used; /* bit l: some triangle has level l */
    uint64_t levels_searched; /* bit l: some triangle of level l searches the grid */
    int top_level;   /* the coarsest level any triangle has */
    double inverse_width[PLANE_GRID_LEVELS]; /* 1 / the width of a cell of each level */
} plane_grid;

typedef struct triangle_order {
    double group_area2; /* the second pass: twice the area of its first pass's cluster */
    double area2;       /* twice its own area; 0: degenerate, never clustered */
    uint32_t triangle;
} triangle_order;

static int larger_area_first(const void *a, const void *b)
{
    const triangle_order *x = a, *y = b;
    if (x->group_area2 != y->group_area2)
        return x->group_area2 > y->group_area2 ? -1 : 1;
    if (x->area2 != y->area2)
        return x->area2 > y->area2 ? -1 : 1;
    return x->triangle < y->triangle ? -1 : (x->triangle > y->triangle);
}

/* a generic direction: which of n and -n is the canonical normal */
static const double generic_direction[3] = {0.3479, 0.5638, 0.7490};

static uint64_t cell_hash(const int32_t key[4])
{
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (int k = 0; k < 4; ++k) {
        h ^= (uint32_t)key[k];
        h *= 0xbf58476d1ce4e5b9ull;
        h ^= h >> 31;
    }
    h *= 0x94d049bb133111ebull;
    return h ^ (h >> 29);
}

static bool grow(void **array, uint64_t *capacity, uint64_t needed, size_t size)
{
    if (needed <= *capacity)
        return true;
    uint64_t next = *capacity ? *capacity : 1024;
    while (next < needed)
        next *= 2;
    if (next > SIZE_MAX / size)
        return false;
    void *grown = realloc(*array, (size_t)(next * size));
    if (!grown)
        return false;
    *array = grown;
    *capacity = next;
    return true;
}

static bool rehash(plane_grid *g)
{
    uint64_t capacity = (g->slot_mask + 1) * 2;
    uint32_t *slots = calloc((size_t)capacity, sizeof *slots);
    if (!slots)
        return false;
    for (uint32_t c = 0; c < g->cell_count; ++c) {
        uint64_t slot = cell_hash(g->cells[c].key) & (capacity - 1);
        while (slots[slot])
            slot = (slot + 1) & (capacity - 1);
        slots[slot] = c + 1;
    }
    free(g->slots);
    g->slots = slots;
    g->slot_mask = capacity - 1;
    return true;
}

/* The cell with this key; created when create is set (NULL on no memory),
 * else NULL when it does not exist. */
static grid_cell *find_cell(plane_grid *g, const int32_t key[4], bool create)
{
    uint64_t slot = cell_hash(key) & g->slot_mask;
    for (; g->slots[slot]; slot = (slot + 1) & g->slot_mask) {
        grid_cell *cell = &g->cells[g->slots[slot] - 1];
        if (memcmp(cell->key, key, sizeof cell->key) == 0)
            return cell;
    }
    if (!create)
        return NULL;
    uint64_t capacity = g->cell_capacity;
    if (!grow((void **)&g->cells, &capacity, (uint64_t)g->cell_count + 1, sizeof *g->cells) ||
        capacity > UINT32_MAX)
        return NULL;
    g->cell_capacity = (uint32_t)capacity;
    grid_cell *cell = &g->cells[g->cell_count];
    memcpy(cell->key, key, sizeof cell->key);
    cell->own = cell->below = cell->last_own = cell->last_below = 0;
    g->slots[slot] = ++g->cell_count;
    if ((uint64_t)g->cell_count * 2 > g->slot_mask + 1 && !rehash(g))
        return NULL;
    return cell;
}

static bool push_entry(plane_grid *g, uint32_t *chain, uint32_t cluster)
{
    if (!grow((void **)&g->entries, &g->entry_capacity, g->entry_count + 1, sizeof *g->entries) ||
        g->entry_count >= UINT32_MAX)
        return false;
    g->entries[g->entry_count] = (grid_entry){cluster, *chain};
    *chain = (uint32_t)++g->entry_count;
    return true;
}

/* A triangle's expanded box: its centre and level. */
typedef struct triangle_box {
    double centre[3];
    int level;
} triangle_box;

static void box_of(const plane_grid *g, const float *a, const float *b, const float *c, double tolerance,
                   triangle_box *box)
{
    double extent = 0.0;
    for (int k = 0; k < 3; ++k) {
        float low = a[k] < b[k] ? a[k] : b[k], high = a[k] < b[k] ? b[k] : a[k];
        low = c[k] < low ? c[k] : low;
        high = c[k] > high ? c[k] : high;
        double lo = (double)low - tolerance, hi = (double)high + tolerance;
        box->centre[k] = 0.5 * (lo + hi);
        extent = hi - lo > extent ? hi - lo : extent;
    }
    /* the smallest level whose cell is at least twice the extent: cell0 x 2^level >= r */
    double r = 2.0 * extent / g->cell0;
    int exponent = 0;
    double fraction = frexp(r, &exponent); /* r = fraction x 2^exponent, fraction in [0.5, 1) */
    int level = r <= 1.0 ? 0 : fraction == 0.5 ? exponent - 1 : exponent;
    box->level = level < PLANE_GRID_LEVELS - 1 ? level : PLANE_GRID_LEVELS - 1;
}

static void cell_key(const plane_grid *g, const double centre[3], int level, int32_t key[4])
{
    key[0] = level;
    for (int k = 0; k < 3; ++k) /* >= 0: the base is below the model's box, so truncating floors */
        key[k + 1] = (int32_t)((centre[k] - g->base[k]) * g->inverse_width[level]);
}

static uint32_t find_root(plane_cluster *clusters, uint32_t c)
{
    while (clusters[c].parent != c) {
        clusters[c].parent = clusters[clusters[c].parent].parent; /* path halving */
        c = clusters[c].parent;
    }
    return c;
}

static bool on_plane(const plane_cluster *cluster, const float *q, double tolerance)
{
    double distance = cluster->normal[0] * q[0] + cluster->normal[1] * q[1] + cluster->normal[2] * q[2] +
                      cluster->d;
    return fabs(distance) <= tolerance;
}

typedef struct plane_search {
    const oit_model *model;
    double tolerance;
    uint32_t *heads; /* the plane hash: chains of clusters + 1 */
    uint64_t head_mask;
    const double *own_planes; /* per triangle: its own plane (4 doubles), the plane hash's key */
    float *offset_slack; /* per triangle: how far the offset of a plane holding it may be from its
                            own; negative: its normal is too uncertain for the plane hash */
    float *lean;         /* per triangle: how far the normal of a plane holding it may be from its own */
    bool use_grid;     /* some triangle is not: the grid is kept */
    plane_grid grid;
    plane_cluster *clusters;
    uint32_t cluster_count;
    uint32_t *member_next; /* per triangle: the next member of its cluster, UINT32_MAX = none */
    uint32_t *candidates;  /* the roots one search found */
    uint32_t candidate_count;
} plane_search;

static bool triangle_on_plane(const plane_search *s, const plane_cluster *cluster, uint32_t t)
{
    const uint32_t *tri = s->model->indices + (size_t)t * 3;
    for (int v = 0; v < 3; ++v)
        if (!on_plane(cluster, s->model->positions + (size_t)tri[v] * 3, s->tolerance))
            return false;
    return true;
}

/* Adds a cluster's root to the candidates, once. */
static void add_candidate(plane_search *s, uint32_t cluster, uint32_t searcher)
{
    uint32_t root = find_root(s->clusters, cluster);
    if (s->clusters[root].stamp == searcher + 1 || s->candidate_count >= PLANE_CANDIDATES_MAX)
        return;
    s->clusters[root].stamp = searcher + 1;
    s->candidates[s->candidate_count++] = root;
}

static void collect(plane_search *s, uint32_t chain, uint32_t searcher)
{
    for (uint32_t e = chain; e && s->candidate_count < PLANE_CANDIDATES_MAX; e = s->grid.entries[e - 1].next)
        add_candidate(s, s->grid.entries[e - 1].cluster, searcher);
}

/* A plane's bucket in the plane hash, and per dimension the nearer neighbour. */
static void plane_key(const double plane[4], double tolerance, int32_t own[4], int32_t nearer[4])
{
    double scaled[4] = {plane[0] * PLANE_NORMAL_STEPS, plane[1] * PLANE_NORMAL_STEPS,
                        plane[2] * PLANE_NORMAL_STEPS, plane[3] / (tolerance * PLANE_OFFSET_STEPS)};
    for (int k = 0; k < 4; ++k) {
        double f = floor(scaled[k]);
        own[k] = (int32_t)f;
        nearer[k] = scaled[k] - f < 0.5 ? own[k] - 1 : own[k] + 1;
    }
}

/* The offset steps a search by plane covers: those of offsets within slack
 * of the plane's. */
static void offset_steps(const double plane[4], double slack, double tolerance, int32_t *first, int32_t *last)
{
    double step = tolerance * PLANE_OFFSET_STEPS;
    *first = (int32_t)floor((plane[3] - slack) / step);
    *last = (int32_t)floor((plane[3] + slack) / step);
}

/* The clusters whose seed plane's normal is within the triangle's lean of
 * its own in each component (its bucket, and the nearer neighbour where the
 * lean reaches across) and whose offset is within its slack. */
static void search_by_plane(plane_search *s, uint32_t t)
{
    const double *plane = s->own_planes + (size_t)t * 4;
    int32_t own[4], nearer[4], first, last;
    plane_key(plane, s->tolerance, own, nearer);
    offset_steps(plane, s->offset_slack[t], s->tolerance, &first, &last);
    int needed = 0; /* bit k: component k's nearer bucket is within the lean */
    for (int k = 0; k < 3; ++k) {
        double within = plane[k] * PLANE_NORMAL_STEPS - own[k], reach = s->lean[t] * PLANE_NORMAL_STEPS;
        if (within - reach < 0.0 || within + reach >= 1.0)
            needed |= 1 << k;
    }
    for (int probe = 0; probe < 8; ++probe) {
        if ((probe & needed) != probe)
            continue;
        for (int32_t offset = first; offset <= last; ++offset) {
            int32_t key[4] = {0, 0, 0, offset};
            for (int k = 0; k < 3; ++k)
                key[k] = (probe >> k) & 1 ? nearer[k] : own[k];
            for (uint32_t c = s->heads[cell_hash(key) & s->head_mask]; c; c = s->clusters[c - 1].next)
                if (memcmp(s->clusters[c - 1].key, key, sizeof key) == 0)
                    add_candidate(s, c - 1, t);
        }
    }
}

/* The 2x2x2 cells nearest a centre at one level: the centre's cell and, per
 * axis, its neighbour on the nearer side. */
static int nearest_cells(const plane_grid *g, const double centre[3], int level, int32_t keys[8][4])
{
    int32_t own[4], side[3];
    cell_key(g, centre, level, own);
    for (int k = 0; k < 3; ++k) {
        double within = (centre[k] - g->base[k]) * g->inverse_width[level] - own[k + 1];
        side[k] = within < 0.5 ? -1 : 1;
    }
    for (int i = 0; i < 8; ++i) {
        keys[i][0] = level;
        for (int k = 0; k < 3; ++k)
            keys[i][k + 1] = own[k + 1] + ((i >> k) & 1 ? side[k] : 0);
    }
    return 8;
}

/* Every cluster root with a triangle whose expanded box may overlap this one. */
static void search_near(plane_search *s, const triangle_box *box, uint32_t searcher)
{
    int32_t keys[8][4];
    for (int level = box->level; level <= s->grid.top_level; ++level) {
        bool own_here = (s->grid.levels_used >> level) & 1;
        if (!own_here && level != box->level)
            continue;
        nearest_cells(&s->grid, box->centre, level, keys);
        for (int i = 0; i < 8; ++i) {
            grid_cell *cell = find_cell(&s->grid, keys[i], false);
            if (!cell)
                continue;
            collect(s, cell->own, searcher);
            if (level == box->level)
                collect(s, cell->below, searcher);
        }
    }
}

/* Registers a triangle of cluster c where a search can meet it: in own at
 * its level when a triangle of that level or a finer one searches, in below
 * at the coarser levels some triangle searches from. A run of one cluster's
 * triangles in a cell is listed once. */
static bool register_triangle(plane_search *s, const triangle_box *box, uint32_t c)
{
    uint64_t own_needed = s->grid.levels_searched & (((uint64_t)2 << box->level) - 1);
    for (int level = box->level; level <= s->grid.top_level; ++level) {
        if (level == box->level ? !own_needed : !((s->grid.levels_searched >> level) & 1))
            continue;
        int32_t key[4];
        cell_key(&s->grid, box->centre, level, key);
        grid_cell *cell = find_cell(&s->grid, key, true);
        if (!cell)
            return false;
        uint32_t *chain = level == box->level ? &cell->own : &cell->below;
        uint32_t *last = level == box->level ? &cell->last_own : &cell->last_below;
        if (*last == c + 1)
            continue;
        if (!push_entry(&s->grid, chain, c))
            return false;
        *last = c + 1;
    }
    return true;
}

static void add_member(plane_search *s, uint32_t root, uint32_t t)
{
    plane_cluster *c = &s->clusters[root];
    s->member_next[t] = UINT32_MAX;
    if (c->size++ == 0)
        c->first = t;
    else
        s->member_next[c->last] = t;
    c->last = t;
}

/* Merges root from into root into when every member of from lies on into's
 * plane; remembers a refusal so the same pair is not scanned again unchanged. */
static void try_merge(plane_search *s, uint32_t into, uint32_t from)
{
    plane_cluster *a = &s->clusters[into], *b = &s->clusters[from];
    if (b->failed_with == into + 1 && b->failed_size == b->size)
        return;
    for (uint32_t t = b->first; t != UINT32_MAX; t = s->member_next[t])
        if (!triangle_on_plane(s, a, t)) {
            b->failed_with = into + 1;
            b->failed_size = b->size;
            return;
        }
    s->member_next[a->last] = b->first;
    a->last = b->last;
    a->size += b->size;
    b->parent = into;
    b->size = 0;
}

/* The root to join first: the largest seed, then the oldest. */
static bool better_root(const plane_cluster *clusters, uint32_t a, uint32_t b)
{
    if (clusters[a].seed_area != clusters[b].seed_area)
        return clusters[a].seed_area > clusters[b].seed_area;
    return a < b;
}

/* How far the offset of a plane that holds this triangle may be from the
 * triangle's own, or -1 where the plane hash cannot find every such plane.
 * A plane holding the three vertices within the tolerance t leans from the
 * triangle's own by at most asin(2 t / h) (h its smallest altitude), so the
 * normals differ by at most pi t / h; the offsets then by that times the
 * centroid's distance from the origin, plus t. The normal probes reach half
 * a step in each component, the normal's sign (towards the generic
 * direction) must not flip within that lean, and the offset probes are
 * bounded. */
static double plane_slack(const plane_search *s, const float *a, const float *b, const float *c, double area2,
                          const double plane[4], const double centroid[3], float *lean_out)
{
    double longest = 0.0;
    const float *v[3] = {a, b, c};
    for (int e = 0; e < 3; ++e) {
        const float *p = v[e], *q = v[(e + 1) % 3];
        double d[3] = {(double)p[0] - q[0], (double)p[1] - q[1], (double)p[2] - q[2]};
        longest = fmax(longest, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    }
    double lean = 3.14159265358979323846 * s->tolerance * longest / area2; /* h = area2 / longest */
    *lean_out = (float)nextafter(lean, INFINITY); /* rounded up: a bound */
    double reach = sqrt(centroid[0] * centroid[0] + centroid[1] * centroid[1] + centroid[2] * centroid[2]);
    double towards = fabs(plane[0] * generic_direction[0] + plane[1] * generic_direction[1] +
                          plane[2] * generic_direction[2]);
    double slack = lean * reach + s->tolerance;
    int32_t first, last;
    offset_steps(plane, slack, s->tolerance, &first, &last);
    return lean < 0.5 / PLANE_NORMAL_STEPS && towards > lean && last - first < PLANE_OFFSET_PROBES_MAX ? slack : -1.0;
}

/* One pass over the triangles in order: each joins the best cluster that
 * holds it of those its searches find (merging the others that hold it
 * where they can), or starts one with its seed plane: its own, or with
 * groups, its group's (5 doubles per group: the plane and the group's
 * area). A triangle first tries the cluster it most likely joins, and
 * searches only if that one does not hold it: the first pass the cluster
 * of the triangle before it (the order keeps faces together), the second
 * the cluster its group's first triangle joined, which searched. So every
 * first-pass group searches at least once in the second pass, and groups
 * of one plane meet there. */
static bool cluster_pass(plane_search *s, const triangle_order *order, const uint32_t *group, const double *fitted,
                         const triangle_box *boxes, uint32_t *group_cluster, uint32_t *cluster_of)
{
    const uint32_t n = s->model->triangle_count;
    s->cluster_count = 0;
    s->grid.cell_count = 0;
    s->grid.entry_count = 0;
    memset(s->grid.slots, 0, (size_t)(s->grid.slot_mask + 1) * sizeof *s->grid.slots);
    memset(s->heads, 0, (size_t)(s->head_mask + 1) * sizeof *s->heads);
    uint32_t previous = UINT32_MAX;
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t t = order[i].triangle;
        const double *plane = group && order[i].area2 > 0.0 ? fitted + (size_t)group[t] * 5
                                                            : s->own_planes + (size_t)t * 4;
        uint32_t chosen = UINT32_MAX;
        uint32_t likely = group ? group_cluster[group[t]] : previous;
        if (likely != UINT32_MAX) {
            likely = find_root(s->clusters, likely);
            if (order[i].area2 > 0.0 && triangle_on_plane(s, &s->clusters[likely], t))
                chosen = likely;
        }
        if (chosen == UINT32_MAX && order[i].area2 > 0.0) {
            s->candidate_count = 0;
            if (s->offset_slack[t] >= 0.0)
                search_by_plane(s, t);
            else
                search_near(s, &boxes[t], t);
            uint32_t accepted = 0;
            for (uint32_t k = 0; k < s->candidate_count; ++k)
                if (triangle_on_plane(s, &s->clusters[s->candidates[k]], t))
                    s->candidates[accepted++] = s->candidates[k];
            for (uint32_t k = 0; k < accepted; ++k)
                if (chosen == UINT32_MAX || better_root(s->clusters, s->candidates[k], chosen))
                    chosen = s->candidates[k];
            for (uint32_t k = 0; k < accepted; ++k)
                if (s->candidates[k] != chosen)
                    try_merge(s, chosen, s->candidates[k]);
        }
        if (chosen == UINT32_MAX) {
            chosen = s->cluster_count++;
            plane_cluster *cluster = &s->clusters[chosen];
            memcpy(cluster->normal, plane, 3 * sizeof(double));
            cluster->d = plane[3];
            cluster->seed_area = order[i].group_area2 > 0.0 ? order[i].group_area2 : order[i].area2;
            cluster->parent = chosen;
            cluster->size = 0;
            cluster->failed_with = cluster->failed_size = 0;
            cluster->stamp = 0;
            cluster->next = 0;
            if (order[i].area2 > 0.0) {
                int32_t nearer[4];
                plane_key(plane, s->tolerance, cluster->key, nearer);
                uint32_t *head = &s->heads[cell_hash(cluster->key) & s->head_mask];
                cluster->next = *head;
                *head = chosen + 1;
            }
        }
        add_member(s, chosen, t);
        cluster_of[t] = chosen;
        previous = chosen;
        if (group && group_cluster[group[t]] == UINT32_MAX)
            group_cluster[group[t]] = chosen;
        if (order[i].area2 > 0.0 && s->use_grid && !register_triangle(s, &boxes[t], chosen))
            return false;
    }
    return true;
}

/* A cluster's plane fitted to all its triangles: the normal of the sum of
 * their area vectors (for a flat region that is its boundary's, so the
 * rounding of inner vertices cancels), through their area-weighted centroid.
 * Kept only if every member still lies within the tolerance of it; else the
 * seed's plane stays. Returns twice the cluster's area. */
static double refit_plane(plane_search *s, uint32_t root, double plane[4])
{
    const plane_cluster *c = &s->clusters[root];
    const oit_model *model = s->model;
    double sum[3] = {0.0, 0.0, 0.0}, weighted[3] = {0.0, 0.0, 0.0}, area2 = 0.0;
    for (uint32_t t = c->first; t != UINT32_MAX; t = s->member_next[t]) {
        const uint32_t *tri = model->indices + (size_t)t * 3;
        const float *a = model->positions + (size_t)tri[0] * 3, *b = model->positions + (size_t)tri[1] * 3,
                    *q = model->positions + (size_t)tri[2] * 3;
        double e1[3] = {(double)b[0] - a[0], (double)b[1] - a[1], (double)b[2] - a[2]};
        double e2[3] = {(double)q[0] - a[0], (double)q[1] - a[1], (double)q[2] - a[2]};
        double v[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double length = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        double sign = v[0] * c->normal[0] + v[1] * c->normal[1] + v[2] * c->normal[2] < 0.0 ? -1.0 : 1.0;
        for (int k = 0; k < 3; ++k) {
            sum[k] += sign * v[k];
            weighted[k] += length * ((double)a[k] + b[k] + q[k]) / 3.0;
        }
        area2 += length;
    }
    memcpy(plane, c->normal, 3 * sizeof(double));
    plane[3] = c->d;
    double length = sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    if (!(length > 0.0) || !(area2 > 0.0) || !isfinite(length))
        return area2;
    plane_cluster fitted = *c;
    double sign = sum[0] * generic_direction[0] + sum[1] * generic_direction[1] + sum[2] * generic_direction[2] < 0.0
                      ? -1.0 : 1.0;
    for (int k = 0; k < 3; ++k)
        fitted.normal[k] = sign * sum[k] / length;
    fitted.d = -(fitted.normal[0] * weighted[0] + fitted.normal[1] * weighted[1] + fitted.normal[2] * weighted[2]) /
               area2;
    for (uint32_t t = c->first; t != UINT32_MAX; t = s->member_next[t])
        if (!triangle_on_plane(s, &fitted, t))
            return area2;
    memcpy(plane, fitted.normal, 3 * sizeof(double));
    plane[3] = fitted.d;
    return area2;
}

/* OIT_COPLANAR_ULPS ulps of the largest file coordinate: the import rounded
 * every coordinate to half an ulp of its own size, so a vertex of a face that
 * is flat in the file lies within an ulp of its plane. */
static double coplanar_tolerance(const oit_model *model)
{
    double largest = 0.0;
    for (int k = 0; k < 3; ++k)
        largest = fmax(largest, fmax(fabs(model->origin[k] + model->bounds_min[k]),
                                     fabs(model->origin[k] + model->bounds_max[k])));
    int exponent;
    frexp(largest > 0.0 ? largest : 1.0, &exponent); /* largest in [2^(e-1), 2^e) */
    return ldexp(OIT_COPLANAR_ULPS, exponent - 1 - 23);  /* float's ulp there: 2^(e-1-23) */
}

/* Two passes: the first clusters with each triangle's own plane as its seed,
 * largest first; the second starts again with each first-pass cluster's
 * fitted plane as the seed of its triangles, the largest clusters first. A
 * seed plane from one small triangle is only as good as its three rounded
 * vertices, so a flat face cut into many small triangles could lose a few to
 * a cluster of their own; the fitted plane averages the rounding away. */
oit_status oit_model_find_planes(oit_model *model, oit_error *err)
{
    const uint32_t n = model->triangle_count;
    const float *p = model->positions;
    plane_search s = {.model = model, .tolerance = coplanar_tolerance(model)};

    free(model->planes);
    free(model->triangle_plane);
    model->planes = NULL;
    model->plane_count = 0;
    model->triangle_plane = malloc((size_t)n * sizeof *model->triangle_plane);
    triangle_order *order = malloc((size_t)n * sizeof *order);
    double *own_planes = malloc((size_t)n * 4 * sizeof *own_planes);
    triangle_box *boxes = malloc((size_t)n * sizeof *boxes);
    uint32_t *group = malloc((size_t)n * sizeof *group);
    double *fitted = NULL;
    uint32_t *group_cluster = NULL;
    triangle_order *group_order = NULL;
    s.own_planes = own_planes;
    s.offset_slack = malloc((size_t)n * sizeof *s.offset_slack);
    s.lean = malloc((size_t)n * sizeof *s.lean);
    s.clusters = malloc((size_t)n * sizeof *s.clusters);
    s.member_next = malloc((size_t)n * sizeof *s.member_next);
    s.candidates = malloc((size_t)n * sizeof *s.candidates);
    s.grid.slots = calloc(1024, sizeof *s.grid.slots);
    s.grid.slot_mask = 1023;
    uint64_t heads = 16;
    while (heads < (uint64_t)n * 2)
        heads *= 2;
    s.heads = malloc((size_t)heads * sizeof *s.heads);
    s.head_mask = heads - 1;
    oit_status status = OIT_OK;
    uint32_t *cluster_of = model->triangle_plane; /* cluster ids first, plane indices at the end */
    if (!model->triangle_plane || !order || !own_planes || !boxes || !group || !s.offset_slack || !s.lean || !s.clusters ||
        !s.member_next || !s.candidates || !s.grid.slots || !s.heads)
        goto out_of_memory;

    for (int k = 0; k < 3; ++k)
        s.grid.base[k] = (double)model->bounds_min[k] - 2.0 * s.tolerance;
    s.grid.cell0 = 4.0 * s.tolerance;
    for (int level = 0; level < PLANE_GRID_LEVELS; ++level)
        s.grid.inverse_width[level] = 1.0 / ldexp(s.grid.cell0, level);
    for (uint32_t t = 0; t < n; ++t) {
        const uint32_t *tri = model->indices + (size_t)t * 3;
        const float *a = p + (size_t)tri[0] * 3, *b = p + (size_t)tri[1] * 3, *c = p + (size_t)tri[2] * 3;
        double e1[3] = {(double)b[0] - a[0], (double)b[1] - a[1], (double)b[2] - a[2]};
        double e2[3] = {(double)c[0] - a[0], (double)c[1] - a[1], (double)c[2] - a[2]};
        double normal[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                            e1[0] * e2[1] - e1[1] * e2[0]};
        double length = sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
        double *plane = own_planes + (size_t)t * 4;
        if (!(length > 0.0) || !isfinite(length)) {
            /* zero area: GL draws nothing; any plane through it will do */
            plane[0] = plane[1] = 0.0;
            plane[2] = 1.0;
            length = 0.0;
        } else {
            double sign = normal[0] * generic_direction[0] + normal[1] * generic_direction[1] +
                                      normal[2] * generic_direction[2] < 0.0
                              ? -1.0 : 1.0;
            for (int k = 0; k < 3; ++k)
                plane[k] = sign * normal[k] / length;
        }
        double centroid[3];
        for (int k = 0; k < 3; ++k)
            centroid[k] = ((double)a[k] + b[k] + c[k]) / 3.0;
        plane[3] = -(plane[0] * centroid[0] + plane[1] * centroid[1] + plane[2] * centroid[2]);
        order[t] = (triangle_order){0.0, length, t};
        box_of(&s.grid, a, b, c, s.tolerance, &boxes[t]);
        s.lean[t] = 0.0f;
        double slack = length > 0.0 ? plane_slack(&s, a, b, c, length, plane, centroid, &s.lean[t]) : -1.0;
        s.offset_slack[t] = slack >= 0.0 ? nextafterf((float)slack, INFINITY) : -1.0f; /* a bound: up */
        s.use_grid = s.use_grid || (length > 0.0 && s.offset_slack[t] < 0.0f);
        if (length > 0.0 && s.offset_slack[t] < 0.0f)
            s.grid.levels_searched |= (uint64_t)1 << boxes[t].level;
        if (length > 0.0) {
            s.grid.levels_used |= (uint64_t)1 << boxes[t].level;
            if (boxes[t].level > s.grid.top_level)
                s.grid.top_level = boxes[t].level;
        }
    }
    qsort(order, n, sizeof *order, larger_area_first);
    if (!cluster_pass(&s, order, NULL, NULL, boxes, NULL, cluster_of))
        goto out_of_memory;

    /* the second pass's seeds and order: the first pass's clusters (groups),
     * fitted, the largest first, each group's triangles in the first pass's
     * order (degenerate triangles last, as before) */
    uint32_t groups = s.cluster_count;
    fitted = malloc((size_t)(groups ? groups : 1) * 5 * sizeof *fitted);
    group_cluster = malloc((size_t)(groups ? groups : 1) * sizeof *group_cluster);
    group_order = malloc((size_t)(groups ? groups : 1) * sizeof *group_order);
    if (!fitted || !group_cluster || !group_order)
        goto out_of_memory;
    uint32_t root_count = 0, placed = 0;
    for (uint32_t c = 0; c < groups; ++c) {
        group_cluster[c] = UINT32_MAX;
        if (s.clusters[c].parent != c || s.clusters[c].seed_area <= 0.0)
            continue;
        fitted[(size_t)c * 5 + 4] = refit_plane(&s, c, fitted + (size_t)c * 5);
        group_order[root_count++] = (triangle_order){fitted[(size_t)c * 5 + 4], 0.0, c};
    }
    qsort(group_order, root_count, sizeof *group_order, larger_area_first);
    for (uint32_t i = 0; i < n; ++i)
        group[order[i].triangle] = find_root(s.clusters, cluster_of[order[i].triangle]);
    triangle_order *second = malloc((size_t)n * sizeof *second);
    if (!second)
        goto out_of_memory;
    for (uint32_t g = 0; g < root_count; ++g) {
        uint32_t c = group_order[g].triangle;
        for (uint32_t t = s.clusters[c].first; t != UINT32_MAX; t = s.member_next[t])
            second[placed++] = (triangle_order){group_order[g].group_area2, 1.0, t};
    }
    for (uint32_t i = 0; i < n; ++i) /* the degenerate ones keep a cluster each */
        if (!(order[i].area2 > 0.0))
            second[placed++] = order[i];
    free(order);
    order = second;
    if (!cluster_pass(&s, order, group, fitted, boxes, group_cluster, cluster_of))
        goto out_of_memory;

    /* planes numbered in the order their clusters were made */
    uint32_t *plane_index = s.candidates; /* reused: per cluster */
    uint32_t count = 0;
    for (uint32_t c = 0; c < s.cluster_count; ++c)
        plane_index[c] = s.clusters[c].parent == c ? count++ : UINT32_MAX;
    model->planes = malloc((size_t)(count ? count : 1) * 4 * sizeof *model->planes);
    if (!model->planes)
        goto out_of_memory;
    for (uint32_t c = 0; c < s.cluster_count; ++c)
        if (plane_index[c] != UINT32_MAX) {
            float *plane = model->planes + (size_t)plane_index[c] * 4;
            for (int k = 0; k < 3; ++k)
                plane[k] = (float)s.clusters[c].normal[k];
            plane[3] = (float)s.clusters[c].d;
        }
    for (uint32_t t = 0; t < n; ++t)
        cluster_of[t] = plane_index[find_root(s.clusters, cluster_of[t])];
    model->plane_count = count;
    goto done;

out_of_memory:
    status = oit_fail(err, OIT_E_RUNTIME, "out of memory finding coplanar faces (%u triangles)", n);
done:
    free(order);
    free(own_planes);
    free(boxes);
    free(group);
    free(fitted);
    free(group_cluster);
    free(group_order);
    free(s.offset_slack);
    free(s.lean);
    free(s.clusters);
    free(s.member_next);
    free(s.candidates);
    free(s.grid.cells);
    free(s.grid.slots);
    free(s.grid.entries);
    free(s.heads);
    return status;
}
