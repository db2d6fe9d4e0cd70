/* assembly.c: building a biological assembly from the generators a reader reported: atom
 * copies (every per-atom array at once, a block per range), coordinates under each
 * operator, and file bonds copied with their atoms. */
#include "config.h"
#include "fileio/assembly.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void gen_free(ms_asm_gen *g)
{
    free(g->id);
    free(g->ranges);
    free(g->ops);
}

void ms_asm_plan_free(ms_asm_plan *p)
{
    for (size_t k = 0; k < p->ngen; k++) gen_free(&p->gen[k]);
    free(p->gen);
    memset(p, 0, sizeof *p);
}

int ms_asm_plan_add(ms_asm_plan *p, const char *id, size_t nranges, const size_t (*ranges)[2],
                    size_t nops, const double (*ops)[12], ms_error *err)
{
    if (nranges == 0 || nops == 0) return 0;
    ms_asm_gen g = {ms_strdup(id ? id : ""), nranges, nops,
                    ms_alloc_array(nranges, sizeof *g.ranges), ms_alloc_array(nops, sizeof *g.ops),
                    0};
    ms_asm_gen *ng = realloc(p->gen, (p->ngen + 1) * sizeof *ng);
    if (ng) p->gen = ng;
    if (!g.id || !g.ranges || !g.ops || !ng) {
        gen_free(&g);
        ms_error_set(err, "out of memory for assembly operators");
        return -1;
    }
    memcpy(g.ranges, ranges, nranges * sizeof *g.ranges);
    memcpy(g.ops, ops, nops * sizeof *g.ops);
    p->gen[p->ngen++] = g;
    return 0;
}

/* The distinct assembly ids, space-separated, for error messages. */
static void list_ids(const ms_asm_plan *all, char *buf, size_t cap)
{
    buf[0] = '\0';
    for (size_t k = 0; k < all->ngen; k++) {
        int seen = 0;
        for (size_t j = 0; j < k && !seen; j++) seen = !strcmp(all->gen[j].id, all->gen[k].id);
        size_t len = strlen(buf);
        if (!seen && len + strlen(all->gen[k].id) + 2 < cap)
            snprintf(buf + len, cap - len, "%s%s", len ? " " : "", all->gen[k].id);
    }
}

/* A few operators over a file's atoms may ask for more atoms than memory holds (no file
 * size bounds that): refuse before anything is copied. An atom costs its per-atom arrays
 * and its first-frame coordinates and velocities. */
static int check_memory(ms_asm_plan *p, const char *id, ms_error *err)
{
    size_t per_atom = 24, avail = ms_mem_available(), elsize;
    ms_atoms none = {0};
    for (size_t k = 0; k < ms_atoms_field_count(); k++) {
        ms_atoms_field(&none, k, &elsize);
        per_atom += elsize;
    }
    double need = (double)ms_asm_natoms(p) * (double)per_atom;
    if (!avail || need <= (double)avail) return 0;
    ms_error_set(err, "assembly '%s' has %zu atoms (from %zu in the file), which need about "
                 "%.0f MB, more than the %.0f MB of memory available", id, ms_asm_natoms(p),
                 p->nfile, need / 1048576, (double)avail / 1048576);
    ms_asm_plan_free(p);
    return -1;
}

int ms_asm_select(const ms_asm_plan *all, const char *id, size_t nfile, ms_asm_plan *out,
                  ms_error *err)
{
    memset(out, 0, sizeof *out);
    out->nfile = nfile;
    for (size_t k = 0; k < all->ngen; k++) {
        const ms_asm_gen *g = &all->gen[k];
        if (strcmp(g->id, id) != 0) continue;
        if (ms_asm_plan_add(out, g->id, g->nranges, (const size_t(*)[2])g->ranges, g->nops,
                            (const double(*)[12])g->ops, err)) {
            ms_asm_plan_free(out);
            return -1;
        }
        ms_asm_gen *c = &out->gen[out->ngen - 1];
        for (size_t r = 0; r < c->nranges; r++) {
            if (c->ranges[r][1] > nfile) c->ranges[r][1] = nfile;
            if (c->ranges[r][0] > c->ranges[r][1]) c->ranges[r][0] = c->ranges[r][1];
            c->natoms += c->ranges[r][1] - c->ranges[r][0];
        }
    }
    if (out->ngen == 0) {
        char ids[256];
        list_ids(all, ids, sizeof ids);
        if (ids[0]) ms_error_set(err, "no assembly '%s' (the file has: %s)", id, ids);
        else ms_error_set(err, "no assembly '%s': the file describes no biological assembly", id);
        return -1;
    }
    if (ms_asm_natoms(out) == 0) {
        ms_error_set(err, "assembly '%s' selects no atoms", id);
        ms_asm_plan_free(out);
        return -1;
    }
    return check_memory(out, id, err);
}

size_t ms_asm_natoms(const ms_asm_plan *p)
{
    size_t n = 0;
    for (size_t k = 0; k < p->ngen; k++) n += p->gen[k].natoms * p->gen[k].nops;
    return n;
}

/* One per-atom array (elsize bytes an atom) of the file to the assembly's. */
static void *expand_array(const ms_asm_plan *p, const void *src, size_t elsize, size_t total)
{
    char *dst = ms_alloc_array(total ? total : 1, elsize), *w = dst;
    if (!dst) return NULL;
    for (size_t k = 0; k < p->ngen; k++) {
        const ms_asm_gen *g = &p->gen[k];
        for (size_t o = 0; o < g->nops; o++)
            for (size_t r = 0; r < g->nranges; r++) {
                size_t n = (g->ranges[r][1] - g->ranges[r][0]) * elsize;
                memcpy(w, (const char *)src + g->ranges[r][0] * elsize, n);
                w += n;
            }
    }
    return dst;
}

/* Segment names "1", "2", ...: copy c of the assembly. */
static int name_copies(ms_molecule *m, const ms_asm_plan *p, ms_error *err)
{
    size_t i = 0, copy = 0;
    for (size_t k = 0; k < p->ngen; k++)
        for (size_t o = 0; o < p->gen[k].nops; o++) {
            char name[32];
            snprintf(name, sizeof name, "%zu", ++copy);
            ms_str id = ms_strtab_intern_cstr(m->strings, name);
            if (id == MS_STR_NONE) {
                ms_error_set(err, "out of memory for segment names");
                return -1;
            }
            for (size_t e = i + p->gen[k].natoms; i < e; i++) m->atoms.segname[i] = id;
        }
    return 0;
}

int ms_asm_expand_atoms(ms_molecule *m, const ms_asm_plan *p, ms_error *err)
{
    size_t total = ms_asm_natoms(p), nf = ms_atoms_field_count();
    if (total > 0x7fffffffu) {
        ms_error_set(err, "the assembly has %zu atoms, more than 2^31", total);
        return -1;
    }
    void **fresh = calloc(nf, sizeof *fresh);
    if (!fresh) goto oom;
    for (size_t k = 0; k < nf; k++) {
        size_t elsize;
        void **field = ms_atoms_field(&m->atoms, k, &elsize);
        if (!(fresh[k] = expand_array(p, *field, elsize, total))) {
            for (size_t j = 0; j < k; j++) free(fresh[j]);
            free(fresh);
            goto oom;
        }
    }
    for (size_t k = 0; k < nf; k++) {
        size_t elsize;
        void **field = ms_atoms_field(&m->atoms, k, &elsize);
        free(*field);
        *field = fresh[k];
    }
    free(fresh);
    m->atoms.n = m->atoms.cap = total;
    return name_copies(m, p, err);
oom:
    ms_error_set(err, "out of memory for an assembly of %zu atoms", total);
    return -1;
}

void ms_asm_expand_xyz(const ms_asm_plan *p, const float *src, float *dst, int vectors)
{
    float *w = dst;
    for (size_t k = 0; k < p->ngen; k++) {
        const ms_asm_gen *g = &p->gen[k];
        for (size_t o = 0; o < g->nops; o++) {
            const double *t = g->ops[o];
            for (size_t r = 0; r < g->nranges; r++)
                for (size_t i = g->ranges[r][0]; i < g->ranges[r][1]; i++, w += 3) {
                    const float *s = src + 3 * i;
                    for (int d = 0; d < 3; d++)
                        w[d] = (float)(t[4 * d] * s[0] + t[4 * d + 1] * s[1] +
                                       t[4 * d + 2] * s[2] + (vectors ? 0.0 : t[4 * d + 3]));
                }
        }
    }
}

int ms_asm_expand_pairs(const ms_asm_plan *p, const uint32_t *pairs, const float *orders,
                        size_t npairs, uint32_t **out, float **out_orders, size_t *nout,
                        ms_error *err)
{
    *out = NULL;
    *out_orders = NULL;
    *nout = 0;
    if (npairs == 0) return 0;
    long *local = ms_alloc_array(p->nfile ? p->nfile : 1, sizeof *local);
    size_t cap = 0, n = 0, ocap = 0;
    uint32_t *v = NULL;
    float *ord = NULL;
    if (!local) goto oom;
    size_t base = 0;
    for (size_t k = 0; k < p->ngen; k++) {
        const ms_asm_gen *g = &p->gen[k];
        for (size_t i = 0; i < p->nfile; i++) local[i] = -1;
        size_t pos = 0;
        for (size_t r = 0; r < g->nranges; r++)
            for (size_t i = g->ranges[r][0]; i < g->ranges[r][1]; i++) local[i] = (long)pos++;
        for (size_t b = 0; b < npairs; b++) {
            uint32_t i = pairs[2 * b], j = pairs[2 * b + 1];
            if (i >= p->nfile || j >= p->nfile || local[i] < 0 || local[j] < 0) continue;
            for (size_t o = 0; o < g->nops; o++) {
                if (ms_grow((void **)&v, &cap, 2 * (n + 1), sizeof *v) ||
                    ms_grow((void **)&ord, &ocap, n + 1, sizeof *ord))
                    goto oom;
                size_t off = base + o * g->natoms;
                v[2 * n] = (uint32_t)(off + (size_t)local[i]);
                v[2 * n + 1] = (uint32_t)(off + (size_t)local[j]);
                ord[n++] = orders ? orders[b] : 1.0f;
            }
        }
        base += g->natoms * g->nops;
    }
    free(local);
    *out = v;
    *out_orders = ord;
    *nout = n;
    return 0;
oom:
    free(local);
    free(v);
    free(ord);
    ms_error_set(err, "out of memory for the assembly's bonds");
    return -1;
}
