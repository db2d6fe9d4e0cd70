/* world.c: the traced world built from a scene: two Embree scenes, one of the opaque and
 * one of the transparent geometries of every placed display list, so that shadow rays can
 * take the opaque scene first and the transparent one only when they got through. A list's
 * spheres, cylinders, cones and discs are moved to world space (place.c) and go straight
 * into them (the instance each transform was placed by until issue 21 cost 4-6% of the
 * tracing on ambient occlusion); its mesh keeps the list's own vertices in a scene of its
 * transform's meshes, placed by an instance. Each list gives one geometry per primitive
 * kind (spheres, cylinders, cones, cap discs, the mesh), its cylinders made first since they
 * take the spheres on their ends (cylinder.c); its lines, points and text (as world-space
 * cylinders and spheres) and its cap discs come from the pass both tracers share
 * (rt_sources_make, common.c); materials become Tachyon's texture terms as the Tachyon
 * exporter writes them (common.c), so the two devices agree. */
#include "config.h"
#include "rt/rt_internal.h"

#include <stdlib.h>
#include <string.h>

const rt_prim *const rt_prims[RT_NKINDS] = {&rt_sphere_prim, &rt_cylinder_prim, &rt_cone_prim,
                                            &rt_ring_prim, &rt_mesh_prim};

/* ---------------------------------------------------------------- helpers */

void *rt_world_alloc(rt_world *w, size_t n, size_t elsize, ms_error *err)
{
    void *p = ms_alloc_array(n ? n : 1, elsize);
    if (!p || ms_grow((void **)&w->owned, &w->capowned, w->nowned + 1, sizeof *w->owned)) {
        free(p);
        ms_error_set(err, "out of memory");
        return NULL;
    }
    w->owned[w->nowned++] = p;
    w->owned_bytes += (n ? n : 1) * elsize;
    return p;
}



static int any_translucent(const ms_rgba8 *c, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (c[i].a < 255) return 1;
    return 0;
}

/* ---------------------------------------------------------------- geometries of a list */

/* The cap discs the sources pass made (rt/common.c). */
static void disc_geom(const rt_discs *d, rt_geom *g)
{
    g->n = d->n, g->a = d->centre, g->b = d->normal, g->ra = d->outer, g->rb = d->inner;
    g->color = d->color;
}

/* The geometry of one kind of a placed list (g->n == 0: none). */
static int fill_geom(const rt_placed *p, rt_kind kind, rt_geom *g)
{
    const ms_displaylist *dl = &p->dl;
    memset(g, 0, sizeof *g);
    g->kind = kind;
    switch (kind) {
    case RT_SPHERE:
        g->n = dl->spheres.n, g->a = dl->spheres.xyz, g->ra = dl->spheres.radius;
        g->color = dl->spheres.color;
        break;
    case RT_CYLINDER:
        g->n = dl->cylinders.n, g->a = dl->cylinders.base, g->b = dl->cylinders.apex;
        g->ra = dl->cylinders.radius, g->color = dl->cylinders.color;
        g->color2 = dl->cylinders.color2, g->joint = dl->cylinders.joint;
        break;
    case RT_CONE:
        g->n = dl->cones.n, g->a = dl->cones.base, g->b = dl->cones.apex;
        g->ra = dl->cones.rbase, g->rb = dl->cones.rapex, g->color = dl->cones.color;
        break;
    case RT_RING:
        disc_geom(&p->discs, g);
        break;
    default:
        if (!dl->mesh.nverts) return 0;
        g->n = dl->mesh.ntris, g->xyz = dl->mesh.xyz, g->normal = dl->mesh.normal;
        g->color = dl->mesh.color, g->tri = dl->mesh.tri;
        g->nverts = dl->mesh.nverts, g->vcap = dl->mesh.vcap;
        g->xf = p->x.xf, g->nm = p->x.nm;      /* the list's vertices, under an instance */
        break;
    }
    return 0;
}

static int no_scene(rt_world *w, ms_error *err)
{
    if (!rt_device_check(w->dev, "Embree scene", err)) ms_error_set(err, "out of memory");
    return -1;
}

/* ---------------------------------------------------------------- the world */

/* A display list to trace: its transform and texture terms. */
typedef rt_source source;

/* Whether a kind of a list may let light through: its material or a colour's alpha. */
static int kind_translucent(const ms_displaylist *dl, const rt_material *mat, rt_kind kind)
{
    if (mat->opacity < 1.0f) return 1;
    switch (kind) {
    case RT_SPHERE: return any_translucent(dl->spheres.color, dl->spheres.n);
    case RT_CYLINDER: return any_translucent(dl->cylinders.color, dl->cylinders.n);
    case RT_CONE: return any_translucent(dl->cones.color, dl->cones.n);
    case RT_RING:
        return any_translucent(dl->cylinders.color, dl->cylinders.n) ||
               any_translucent(dl->cones.color, dl->cones.n);
    default: return any_translucent(dl->mesh.color, dl->mesh.nverts);
    }
}

/* Whether a source's opaque or transparent part holds user geometries: cylinders, cones or
 * their cap discs. Its spheres then join them as a user geometry (they meet: Licorice's
 * spheres cap its bonds), while another list's spheres (VDW beside Licorice) stay Embree's
 * own: on the benchmark that traced 9% faster than all spheres in the user tree. */
static int has_user_kinds(const source *src, int trans)
{
    const ms_displaylist *dl = src->dl;
    return (dl->cylinders.n && kind_translucent(dl, &src->mat, RT_CYLINDER) == trans) ||
           (dl->cones.n && kind_translucent(dl, &src->mat, RT_CONE) == trans);
}

/* The spheres of g that no cylinder took (g's arrays replaced by copies). */
static int keep_spheres(rt_world *w, rt_geom *g, const uint8_t *taken, ms_error *err)
{
    size_t m = 0;
    for (size_t i = 0; i < g->n; i++) m += !taken[i];
    float *c = rt_world_alloc(w, 3 * m, sizeof(float), err), *r = rt_world_alloc(w, m, sizeof(float), err);
    ms_rgba8 *col = rt_world_alloc(w, m, sizeof(ms_rgba8), err);
    if (!c || !r || !col) return -1;
    for (size_t i = 0, k = 0; i < g->n; i++) {
        if (taken[i]) continue;
        memcpy(c + 3 * k, g->a + 3 * i, 3 * sizeof(float));
        r[k] = g->ra[i];
        col[k++] = g->color[i];
    }
    g->n = m, g->a = c, g->ra = r, g->color = col;
    return 0;
}

/* The geometry of a source's kind (placed as p) into scene sc with Embree id, when its
 * transparency is trans; user: spheres join the user geometries' tree, and the cylinders
 * take the spheres on their ends (*taken: which, for the spheres that follow). 1 when it
 * made one (w->geoms' last), 0 when the list has none, -1 with err set. */
static int add_geom(rt_world *w, RTCScene sc, unsigned id, const source *src, const rt_placed *p,
                    rt_kind kind, int trans, int user, uint8_t **taken, ms_error *err)
{
    if (kind_translucent(src->dl, &src->mat, kind) != trans) return 0;
    rt_geom *g = &w->geoms[w->ngeoms];
    fill_geom(p, kind, g);
    g->user = user;
    g->item = src->item;
    if (kind == RT_CYLINDER && user && kind_translucent(src->dl, &src->mat, RT_SPHERE) == trans)
        g->spheres = &p->dl.spheres;
    if (kind == RT_SPHERE && *taken && keep_spheres(w, g, *taken, err)) return -1;
    if (!g->n) return 0;
    if (g->n > 0xffffffffu) {
        ms_error_set(err, "%s: more than 2^32 in one list", rt_prims[kind]->name);
        return -1;
    }
    g->mat = src->mat;
    g->alpha = any_translucent(g->color, kind == RT_MESH ? g->nverts : g->n);
    g->transparent = trans;
    RTCGeometry geom = rt_prims[kind]->geometry(w, g, err);
    if (!geom) return -1;
    if (kind == RT_CYLINDER) *taken = g->taken;
    rtcSetGeometryUserData(geom, g);
    int clipped = g->item && g->item->nclip;
    if ((trans || clipped) && ((kind == RT_SPHERE && !user) || kind == RT_MESH))
        rtcSetGeometryOccludedFilterFunction(geom, rt_occlusion_filter);
    /* A transparent mesh's tree by Morton codes rather than SAH: on the benchmark's 1M
     * triangles 0.3 s of CPU less to build, 0.14 s more to trace a pass of 1024 x 1024; so
     * when the camera rays are fewer than twice its triangles (a one-pass render) */
    if (trans && kind == RT_MESH && w->samples > 0 && w->samples < 2.0 * (double)g->n) {
        rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_LOW);
        g->morton = 1;
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(sc, geom, id);
    rtcReleaseGeometry(geom);
    w->ngeoms++;
    w->has_trans |= trans;
    return 1;
}

/* Mesh triangles of the scene. */
static size_t scene_triangles(const ms_scene *s)
{
    size_t tris = 0;
    for (size_t i = 0; i < s->nitems; i++) tris += s->items[i].dl->mesh.ntris;
    return tris;
}

/* Mesh triangles of the sources sharing the transform of source first. */
static size_t group_triangles(const rt_world *w, size_t first)
{
    size_t tris = 0;
    for (size_t i = first; i < w->set.n; i++)
        if (w->placed[i].group == first) tris += w->set.src[i].dl->mesh.ntris;
    return tris;
}

/* Compact leaves: Triangle4i leaves that index the list's own vertices instead of copying
 * them, and smaller nodes. On the scale benchmark's 1M-atom QuickSurf (2.9M triangles)
 * Embree's peak went from 342 to 147 MB, the image identical (a low-quality, Morton-code
 * build of the same scene peaked at 248 MB). But a ray costs more: on the Table 2 scene
 * (nested QuickSurf surfaces, issue 21) compact leaves traced 30-40% slower at 56 k, 500 k
 * and 2.4 M atoms, an opaque surface with AO 15% slower at 13 rays a triangle; the fast
 * layout builds slower and takes 2.3 times the memory, whose first touch is itself slow
 * (the 4M-atom scale benchmark, 2.8 rays a triangle: 25% more CPU, none of it saved in the
 * trace; the 1M one, 11: the same CPU; the Table 2 scene at 2.4 M atoms, 3.4 rays a
 * triangle: 13% less CPU, 26% at 13.5). A scene's large meshes (COMPACT_TRIS
 * and more) therefore get the fast layout only when it takes at most half of what Embree
 * may hold (rt_device_room, from the render's memory plan; with no plan, never) and the
 * render's rays (estimated: rt_rays_per_sample) are at least RAYS_PER_TRI_FAST a triangle. */
#define COMPACT_TRIS ((size_t)1 << 20)
#define RAYS_PER_TRI_FAST 3.0

/* Embree's bytes a primitive, taken low: the scale benchmark's QuickSurf triangles peaked at
 * 52 bytes each compact and 119 otherwise (BVH, leaves and the build's references); the
 * other primitives are user geometries with at least a reference and a node share each. */
#define EST_TRI_COMPACT 48
#define EST_TRI 100
#define EST_TRI_FAST 120      /* as measured (119), to choose the layout */
#define EST_OTHER 64

/* Whether the world's large meshes get compact leaves (above), for about rays rays (0:
 * unknown, as for a session: the live view builds its world again at every change of the
 * view, so the quicker build is kept there). */
static int use_compact(double rays, size_t tris, size_t nother)
{
    if (tris < COMPACT_TRIS) return 0;
    size_t room = rt_device_room();
    if (!room || (double)tris * EST_TRI_FAST + (double)nother * EST_OTHER > (double)room / 2)
        return 1;
    return !(rays >= RAYS_PER_TRI_FAST * (double)tris);
}

/* Whether a scene of tris triangles gets compact leaves. */
static int scene_compact(const rt_world *w, size_t tris)
{
    return w->compact && tris >= COMPACT_TRIS;
}

/* A new Embree scene for opaque or transparent geometries, with tris triangles in all; NULL
 * with err set. */
static RTCScene new_scene(rt_world *w, int trans, size_t tris, ms_error *err)
{
    RTCScene sc = rtcNewScene(w->dev);
    if (!sc) {
        no_scene(w, err);
        return NULL;
    }
    /* the transparent part is walked only by rays the opaque part let through: a quick build
     * traced as fast there (measured on a 1M-triangle surface: 0.3 s of CPU saved) */
    rtcSetSceneBuildQuality(sc, trans ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM);
    if (scene_compact(w, tris)) rtcSetSceneFlags(sc, RTC_SCENE_FLAG_COMPACT);
    return sc;
}

/* The meshes of the sources sharing source first's transform (when trans, their transparent
 * ones): a scene of the lists' own vertices, placed in the world's scene by an instance of
 * the transform (moving the vertices would copy 12 bytes of each). */
static int add_meshes(rt_world *w, size_t first, int trans, ms_error *err)
{
    size_t tris = group_triangles(w, first);
    RTCScene sub = new_scene(w, trans, tris, err);
    if (!sub) return -1;
    rt_geom *g0 = &w->geoms[w->ngeoms];
    unsigned n = 0;
    for (size_t i = first; i < w->set.n; i++) {
        if (w->placed[i].group != first) continue;
        int rc = add_geom(w, sub, n, &w->set.src[i], &w->placed[i], RT_MESH, trans, 0, NULL, err);
        if (rc < 0) goto fail;
        if (rc) w->geoms[w->ngeoms - 1].compact = (uint8_t)scene_compact(w, tris);
        n += (unsigned)rc;
    }
    rtcCommitScene(sub);
    if (rt_device_check(w->dev, "Embree build", err)) goto fail;
    if (n) {
        RTCGeometry inst = rtcNewGeometry(w->dev, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(inst, sub);
        rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, w->placed[first].x.xf);
        rtcCommitGeometry(inst);
        rtcAttachGeometryByID(w->scene[trans], inst, (unsigned)w->npart[trans]);
        rtcReleaseGeometry(inst);
        w->part[trans][w->npart[trans]++] = g0;
    }
    rtcReleaseScene(sub);
    return rt_device_check(w->dev, "Embree instance", err);
fail:
    rtcReleaseScene(sub);
    return -1;
}

/* The Embree scene of every placed list's opaque or transparent geometries: the world-space
 * ones, then an instance per transform with meshes. */
static int add_scene(rt_world *w, const ms_scene *s, int trans, ms_error *err)
{
    RTCScene sc = w->scene[trans] = new_scene(w, trans, scene_triangles(s), err);
    w->part[trans] = rt_world_alloc(w, w->set.n * RT_NKINDS, sizeof(rt_geom *), err);
    if (!sc || !w->part[trans]) return -1;
    /* cylinders first: they may take the spheres on their ends */
    static const rt_kind order[] = {RT_CYLINDER, RT_SPHERE, RT_CONE, RT_RING};
    for (size_t i = 0; i < w->set.n; i++) {
        const source *src = &w->set.src[i];
        uint8_t *taken = NULL;
        for (int k = 0; k < 4 && !w->placed[i].skip; k++) {
            rt_geom *g = &w->geoms[w->ngeoms];
            int rc = add_geom(w, sc, (unsigned)w->npart[trans], src, &w->placed[i], order[k], trans,
                              has_user_kinds(src, trans), &taken, err);
            if (rc < 0) return -1;
            if (rc) w->part[trans][w->npart[trans]++] = g;
        }
    }
    for (size_t i = 0; i < w->set.n; i++)
        if (w->placed[i].group == i && !w->placed[i].skip && add_meshes(w, i, trans, err)) return -1;
    rtcCommitScene(sc);
    return rt_device_check(w->dev, "Embree build", err);
}

/* Every source's list in world space, and the first source of its transform. */
static int place_sources(rt_world *w, ms_error *err)
{
    const source *src = w->set.src;
    for (size_t i = 0; i < w->set.n; i++) {
        int rc = rt_place(w, &src[i], &w->placed[i], err);
        if (rc < 0) return -1;
        w->placed[i].skip = rc > 0;
        size_t j = 0;
        while (j < i && memcmp(src[j].xform, src[i].xform, 16 * sizeof(float))) j++;
        w->placed[i].group = j;
    }
    return 0;
}

size_t rt_world_estimate(const ms_scene *s, size_t *ntris, size_t *nother)
{
    *ntris = scene_triangles(s);
    *nother = 0;
    for (size_t i = 0; i < s->nitems; i++) {
        const ms_displaylist *dl = s->items[i].dl;
        *nother += dl->spheres.n + dl->cylinders.n + dl->cones.n + dl->lines.n + dl->points.n;
    }
    return *ntris * (*ntris >= COMPACT_TRIS ? EST_TRI_COMPACT : EST_TRI) + *nother * EST_OTHER;
}

int rt_world_build(rt_world *w, const ms_scene *s, double samples, double rays, int leaves,
                   ms_error *err)
{
    memset(w, 0, sizeof *w);
    w->samples = samples;
    w->dev = rt_device(err);
    if (!w->dev) return -1;
    w->eps = rt_world_eps(s);
    size_t ntris, nother;
    rt_world_estimate(s, &ntris, &nother);
    w->compact = leaves == MS_RT_LEAVES_AUTO ? use_compact(rays, ntris, nother)
                                             : leaves == MS_RT_LEAVES_COMPACT;
    if (rt_sources_make(&w->set, s, err)) goto fail;
    w->placed = rt_world_alloc(w, w->set.n, sizeof *w->placed, err);
    w->geoms = rt_world_alloc(w, w->set.n * RT_NKINDS, sizeof *w->geoms, err);
    if (!w->placed || !w->geoms || place_sources(w, err) || add_scene(w, s, RT_OPAQUE, err) ||
        add_scene(w, s, RT_TRANS, err))
        goto fail;
    if (!w->npart[RT_TRANS]) {          /* nothing transparent: shadow rays walk one scene */
        rtcReleaseScene(w->scene[RT_TRANS]);
        w->scene[RT_TRANS] = NULL;
    }
    return 0;
fail:
    rt_world_free(w);
    return -1;
}

void rt_world_free(rt_world *w)
{
    for (int k = 0; k < 2; k++)
        if (w->scene[k]) rtcReleaseScene(w->scene[k]);
    for (size_t i = 0; i < w->nowned; i++) free(w->owned[i]);
    free(w->owned);
    rt_sources_free(&w->set);
    memset(w, 0, sizeof *w);
}
