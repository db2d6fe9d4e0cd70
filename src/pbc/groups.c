/* groups.c: atoms grouped into the compounds pbctools moves as a whole: residues, segments,
 * chains, fragments, or atoms bonded to each other within the atoms given. Each atom gets a
 * key, the keys are numbered densely, and a counting sort lays the atoms out compound by
 * compound (ascending inside each). Also runs of consecutive atoms, what the vectorised
 * loops take when atoms move alone. */
#include "config.h"
#include "pbc/internal.h"

#include <stdlib.h>
#include <string.h>

void ms_pbc_groups_free(ms_pbc_groups *g)
{
    free(g->start);
    free(g->atoms);
    memset(g, 0, sizeof *g);
}

static uint32_t uf_find(uint32_t *parent, uint32_t i)
{
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

/* Keys of CONNECTED: the root of each atom's bonded group within the atoms. */
static int connected_keys(const ms_molecule *m, const uint32_t *atoms, size_t n, uint32_t *key)
{
    uint32_t *parent = ms_alloc_array(m->atoms.n, sizeof *parent);
    uint8_t *in = calloc(m->atoms.n ? m->atoms.n : 1, 1);
    if (!parent || !in) {
        free(parent);
        free(in);
        return -1;
    }
    for (size_t i = 0; i < m->atoms.n; i++) parent[i] = (uint32_t)i;
    for (size_t i = 0; i < n; i++) in[atoms[i]] = 1;
    for (size_t i = 0; m->has_bonds && i < n; i++) {
        uint32_t a = atoms[i];
        for (uint32_t b = m->bonds.start[a]; b < m->bonds.start[a + 1]; b++) {
            uint32_t o = m->bonds.to[b];
            if (!in[o]) continue;
            uint32_t ra = uf_find(parent, a), ro = uf_find(parent, o);
            if (ra != ro) parent[ra > ro ? ra : ro] = ra < ro ? ra : ro;
        }
    }
    for (size_t i = 0; i < n; i++) key[i] = uf_find(parent, atoms[i]);
    free(parent);
    free(in);
    return 0;
}

static int compound_keys(const ms_molecule *m, int kind, const uint32_t *atoms, size_t n,
                         uint32_t *key)
{
    const ms_atoms *a = &m->atoms;
    for (size_t i = 0; i < n; i++) {
        uint32_t k = atoms[i];
        switch (kind) {
        case MS_PBC_RESIDUE: key[i] = (uint32_t)a->residue[k]; break;
        case MS_PBC_SEGMENT: key[i] = a->segname[k]; break;
        case MS_PBC_CHAIN: key[i] = a->chain[k]; break;
        case MS_PBC_FRAGMENT: key[i] = (uint32_t)a->fragment[k]; break;
        case MS_PBC_CONNECTED: return connected_keys(m, atoms, n, key);
        default: key[i] = (uint32_t)i; break;
        }
    }
    return 0;
}

/* Number the keys 0.. in order of first appearance (key[] rewritten), return the count. */
static long dense_keys(uint32_t *key, size_t n)
{
    uint32_t max = 0;
    for (size_t i = 0; i < n; i++) if (key[i] > max) max = key[i];
    uint32_t *map = ms_alloc_array((size_t)max + 1, sizeof *map);
    if (!map) return -1;
    memset(map, 0xff, ((size_t)max + 1) * sizeof *map);
    uint32_t next = 0;
    for (size_t i = 0; i < n; i++) {
        if (map[key[i]] == UINT32_MAX) map[key[i]] = next++;
        key[i] = map[key[i]];
    }
    free(map);
    return next;
}

static int lay_out(ms_pbc_groups *g, const uint32_t *atoms, const uint32_t *key, size_t n)
{
    g->start = calloc(g->n + 1, sizeof *g->start);
    g->atoms = ms_alloc_array(n ? n : 1, sizeof *g->atoms);
    if (!g->start || !g->atoms) return -1;
    for (size_t i = 0; i < n; i++) g->start[key[i] + 1]++;
    for (size_t k = 0; k < g->n; k++) g->start[k + 1] += g->start[k];
    uint32_t *fill = ms_alloc_array(g->n ? g->n : 1, sizeof *fill);
    if (!fill) return -1;
    memcpy(fill, g->start, g->n * sizeof *fill);
    for (size_t i = 0; i < n; i++) g->atoms[fill[key[i]]++] = atoms[i];
    free(fill);
    return 0;
}

int ms_pbc_groups_make(const ms_molecule *m, int kind, const uint32_t *atoms, size_t n,
                       ms_pbc_groups *g, ms_error *err)
{
    memset(g, 0, sizeof *g);
    uint32_t *key = ms_alloc_array(n ? n : 1, sizeof *key);
    long count = -1;
    if (key && compound_keys(m, kind, atoms, n, key) == 0) count = dense_keys(key, n);
    if (count >= 0) {
        g->n = (size_t)count;
        if (lay_out(g, atoms, key, n)) count = -1;
    }
    free(key);
    if (count < 0) {
        ms_pbc_groups_free(g);
        ms_error_set(err, "out of memory grouping %zu atoms into compounds", n);
        return -1;
    }
    return 0;
}

int ms_pbc_runs_make(const uint32_t *atoms, size_t n, size_t maxlen, ms_pbc_runs *r)
{
    size_t count = 0;
    for (size_t i = 0, len = 0; i < n; i++, len++)
        if (i == 0 || atoms[i] != atoms[i - 1] + 1 || len == maxlen) count++, len = 0;
    r->n = count;
    r->run = ms_alloc_array(count ? count : 1, sizeof *r->run);
    if (!r->run) return -1;
    for (size_t i = 0, k = 0, len = 0; i < n; i++, len++) {
        if (i == 0 || atoms[i] != atoms[i - 1] + 1 || len == maxlen)
            r->run[k][0] = atoms[i], r->run[k++][1] = 0, len = 0;
        r->run[k - 1][1]++;
    }
    return 0;
}
