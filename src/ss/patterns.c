/* patterns.c: DSSP's patterns over the hydrogen bonds (Kabsch & Sander 1983), in their
 * order of priority:
 *   - bridges: parallel when Hbond(i-1,j) and Hbond(j,i+1), or Hbond(j-1,i) and
 *     Hbond(i,j+1); antiparallel when Hbond(i,j) and Hbond(j,i), or Hbond(i-1,j+1) and
 *     Hbond(j-1,i+1) (Hbond(a,b): C=O of a to N-H of b); consecutive bridges of one type
 *     form a ladder, ladders joined by a bulge (at most 1 extra residue on one strand and 4
 *     on the other) are one ladder; residues of ladders of two or more bridges are E,
 *     of lone bridges B;
 *   - an n-turn at i is Hbond(i, i+n), n = 3, 4, 5; two turns at i-1 and i make a minimal
 *     helix over i..i+n-1: H for n = 4 (over anything), then G (n = 3) and I (n = 5) only
 *     where the residues are still coil or of the same kind;
 *   - residues inside a turn (i+1..i+n-1) still coil are T.
 * No pattern crosses a chain break. Bridges are found from each residue's hydrogen bonds,
 * never by trying all pairs, so the work is linear. */
#include "config.h"
#include "ss/ssint.h"

#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- turns and helices */

/* Bit n-3 of turn[i]: an n-turn starts at i. */
static void find_turns(const ms_ss_chain *c, uint8_t *turn)
{
    for (size_t i = 0; i < c->n; i++) {
        turn[i] = 0;
        for (size_t n = 3; n <= 5; n++)
            if (i + n < c->n && c->piece[i] == c->piece[i + n] && ms_ss_bonded(c, i + n, i))
                turn[i] |= (uint8_t)(1u << (n - 3));
    }
}

static int starts(const uint8_t *turn, size_t i, size_t n)
{
    return (turn[i] >> (n - 3)) & 1u;
}

/* Minimal helices of n-turns: code over i..i+n-1 where turns start at i-1 and i; unless
 * `over_all`, only where every residue is coil or already `code`. */
static void helices(const ms_ss_chain *c, const uint8_t *turn, size_t n, char code,
                    int over_all, char *ss)
{
    for (size_t i = 1; i + n < c->n; i++) {
        if (!starts(turn, i - 1, n) || !starts(turn, i, n)) continue;
        int vacant = 1;
        for (size_t k = i; vacant && !over_all && k < i + n; k++)
            vacant = ss[k] == MS_SS_COIL_CODE || ss[k] == code;
        if (vacant) memset(ss + i, code, n);
    }
}

static void turns(const ms_ss_chain *c, const uint8_t *turn, char *ss)
{
    for (size_t i = 1; i < c->n; i++) {
        if (ss[i] != MS_SS_COIL_CODE) continue;
        int in_turn = 0;
        for (size_t n = 3; n <= 5 && !in_turn; n++)
            for (size_t k = 1; k < n && k <= i && !in_turn; k++) in_turn = starts(turn, i - k, n);
        if (in_turn) ss[i] = 'T';
    }
}

/* ---------------------------------------------------------------- bridges and ladders */

enum { PARALLEL = 1, ANTIPARALLEL = 2 };

/* A ladder: residues i0..i1 paired with j0..j1 (i0 < j0), nbridges bridges. */
typedef struct ladder {
    int type;
    size_t i0, i1, j0, j1, nbridges;
    int dead;                 /* merged into another */
} ladder;

typedef struct ladders {
    ladder *l;
    size_t n, cap;
    size_t *prev, nprev, *cur, ncur;   /* ladders whose i side ends at i-1, and at i */
} ladders;

static int bridge_type(const ms_ss_chain *c, size_t i, size_t j)
{
    if (i < 1 || j + 1 >= c->n || j < i + 3) return 0;
    if (c->piece[i - 1] != c->piece[i + 1] || c->piece[j - 1] != c->piece[j + 1]) return 0;
    if ((ms_ss_bonded(c, i + 1, j) && ms_ss_bonded(c, j, i - 1)) ||
        (ms_ss_bonded(c, j + 1, i) && ms_ss_bonded(c, i, j - 1)))
        return PARALLEL;
    if ((ms_ss_bonded(c, i + 1, j - 1) && ms_ss_bonded(c, j + 1, i - 1)) ||
        (ms_ss_bonded(c, j, i) && ms_ss_bonded(c, i, j)))
        return ANTIPARALLEL;
    return 0;
}

/* Partners j > i that could bridge with i: every bridge pattern has a bond from the N-H
 * of i or i+1 to the C=O of j or j-1, so j is an acceptor of i or i+1, or one past one.
 * Written ascending, without repeats, into js (at most 8); returns how many. */
static size_t candidates(const ms_ss_chain *c, size_t i, size_t js[8])
{
    size_t n = 0;
    for (size_t d = i; d <= i + 1 && d < c->n; d++)
        for (int b = 0; b < 2; b++) {
            int32_t a = c->acc[2 * d + (size_t)b];
            if (a < 0) continue;
            for (size_t j = (size_t)a; j <= (size_t)a + 1; j++) {
                size_t k = n;
                while (k > 0 && js[k - 1] > j) k--;
                if (j <= i || (k > 0 && js[k - 1] == j)) continue;
                memmove(js + k + 1, js + k, (n - k) * sizeof *js);
                js[k] = j;
                n++;
            }
        }
    return n;
}

/* Add bridge (i, j) to the ladder it continues (one whose i side ends at i-1 with j next
 * to its j side) or start a new one. */
static int add_bridge(ladders *L, int type, size_t i, size_t j)
{
    for (size_t q = 0; q < L->nprev; q++) {
        ladder *l = &L->l[L->prev[q]];
        if (l->type != type || l->i1 + 1 != i) continue;
        if (type == PARALLEL ? l->j1 + 1 != j : l->j0 != j + 1) continue;
        l->i1 = i;
        if (type == PARALLEL) l->j1 = j;
        else l->j0 = j;
        l->nbridges++;
        L->cur[L->ncur++] = L->prev[q];
        return 0;
    }
    if (ms_grow((void **)&L->l, &L->cap, L->n + 1, sizeof *L->l)) return -1;
    L->l[L->n] = (ladder){type, i, i, j, j, 1, 0};
    L->cur[L->ncur++] = L->n++;
    return 0;
}

static int find_ladders(const ms_ss_chain *c, ladders *L)
{
    size_t store[2][8];
    L->prev = store[0];
    L->cur = store[1];
    L->nprev = L->ncur = 0;
    for (size_t i = 1; i + 1 < c->n; i++) {
        size_t js[8], nj = candidates(c, i, js);
        for (size_t k = 0; k < nj; k++) {
            int type = bridge_type(c, i, js[k]);
            if (type && add_bridge(L, type, i, js[k])) return -1;
        }
        size_t *t = L->prev;   /* the ladders touched at i are the ones i+1 may extend */
        L->prev = L->cur;
        L->nprev = L->ncur;
        L->cur = t;
        L->ncur = 0;
    }
    L->prev = L->cur = NULL;
    return 0;
}

static long lmin(size_t a, size_t b) { return (long)(a < b ? a : b); }
static long lmax(size_t a, size_t b) { return (long)(a > b ? a : b); }

/* May ladder b (starting at or after a on the i side) join a across a bulge? */
static int bulge(const ms_ss_chain *c, const ladder *a, const ladder *b)
{
    if (a->type != b->type) return 0;
    if (c->seg[lmin(a->i0, b->i0)] != c->seg[lmax(a->i1, b->i1)] ||
        c->seg[lmin(a->j0, b->j0)] != c->seg[lmax(a->j1, b->j1)])
        return 0;
    if (a->i1 >= b->i0 && a->i0 <= b->i1) return 0;   /* overlapping on the i side */
    long igap = (long)b->i0 - (long)a->i1;
    long jgap = a->type == PARALLEL ? (long)b->j0 - (long)a->j1 : (long)a->j0 - (long)b->j1;
    return jgap >= 0 && ((jgap < 6 && igap < 3) || jgap < 3);
}

/* Join ladders across bulges. Ladders are in order of i0, so the scan for partners of a
 * stops at the first one starting 6 or more residues past a's end. */
static void merge_bulges(const ms_ss_chain *c, ladders *L)
{
    for (size_t p = 0; p < L->n; p++) {
        ladder *a = &L->l[p];
        if (a->dead) continue;
        for (size_t q = p + 1; q < L->n; q++) {
            ladder *b = &L->l[q];
            if ((long)b->i0 - (long)a->i1 >= 6) break;
            if (b->dead || !bulge(c, a, b)) continue;
            a->i0 = (size_t)lmin(a->i0, b->i0);
            a->i1 = (size_t)lmax(a->i1, b->i1);
            a->j0 = (size_t)lmin(a->j0, b->j0);
            a->j1 = (size_t)lmax(a->j1, b->j1);
            a->nbridges += b->nbridges;
            b->dead = 1;
        }
    }
}

static void mark_strand(size_t from, size_t to, char code, char *ss)
{
    for (size_t r = from; r <= to; r++)
        if (ss[r] != 'E') ss[r] = code;
}

static int sheets(const ms_ss_chain *c, char *ss, ms_error *err)
{
    ladders L = {NULL, 0, 0, NULL, 0, NULL, 0};
    if (find_ladders(c, &L)) {
        free(L.l);
        ms_error_set(err, "out of memory for beta ladders");
        return -1;
    }
    merge_bulges(c, &L);
    for (size_t p = 0; p < L.n; p++) {
        const ladder *l = &L.l[p];
        if (l->dead) continue;
        char code = l->nbridges > 1 ? 'E' : 'B';
        mark_strand(l->i0, l->i1, code, ss);
        mark_strand(l->j0, l->j1, code, ss);
    }
    free(L.l);
    return 0;
}

/* ---------------------------------------------------------------- all together */

int ms_ss_patterns(const ms_ss_chain *c, char *ss, ms_error *err)
{
    if (c->n == 0) return 0;
    uint8_t *turn = malloc(c->n);
    if (!turn) {
        ms_error_set(err, "out of memory for turns of %zu residues", c->n);
        return -1;
    }
    find_turns(c, turn);
    int rc = sheets(c, ss, err);
    if (rc == 0) {
        helices(c, turn, 4, 'H', 1, ss);
        helices(c, turn, 3, 'G', 0, ss);
        helices(c, turn, 5, 'I', 0, ss);
        turns(c, turn, ss);
    }
    free(turn);
    return rc;
}
