/* test_serialize.c: unit tests of molecule serialisation: a round trip of a real structure
 * (1tii.pdb, with extra frames, velocities, user values, bond orders and types added) must
 * give back every array unchanged, through one buffer and through header + blocks as the
 * MPI broadcast sends them; damaged buffers give errors, never crashes. The PDB plugin is
 * linked in directly. */
#include "config.h"
#include "ms_test.h"
#include "fileio/load.h"
#include "molecule/analysis.h"
#include "molecule/serialize.h"

#include <string.h>

#include "builtin/builtin.h"

#include "ms_testload.h"

/* ---------------------------------------------------------------- comparison */

static int same_bytes(const void *a, const void *b, size_t n)
{
    if (!n) return 1;
    if (!a || !b) return a == b;
    return memcmp(a, b, n) == 0;
}

static int same_str(const char *a, const char *b)
{
    return (!a && !b) || (a && b && strcmp(a, b) == 0);
}

/* The first difference between two molecules, or NULL when there is none. */
static const char *difference(ms_molecule *a, ms_molecule *b)
{
    static char why[128];
    size_t n = a->atoms.n;
    if (b->atoms.n != n) return "atom count";
    for (size_t k = 0; k < ms_atoms_field_count(); k++) {
        size_t el;
        void **pa = ms_atoms_field(&a->atoms, k, &el), **pb = ms_atoms_field(&b->atoms, k, &el);
        if (!same_bytes(*pa, *pb, n * el)) {
            snprintf(why, sizeof why, "per-atom array %zu", k);
            return why;
        }
    }
    uint32_t ns = ms_strtab_count(a->strings);
    if (ms_strtab_count(b->strings) != ns) return "string count";
    for (uint32_t id = 0; id < ns; id++)
        if (strcmp(ms_strtab_get(a->strings, id), ms_strtab_get(b->strings, id))) return "a string";
    if (a->has_bonds != b->has_bonds) return "has_bonds";
    size_t nb = a->has_bonds ? a->bonds.start[n] : 0;
    if (a->has_bonds && (!same_bytes(a->bonds.start, b->bonds.start, (n + 1) * 4) ||
                         !same_bytes(a->bonds.to, b->bonds.to, nb * 4)))
        return "bond table";
    if (!a->bonds.order != !b->bonds.order || !same_bytes(a->bonds.order, b->bonds.order, nb * 4))
        return "bond orders";
    if (!a->bonds.type != !b->bonds.type || !same_bytes(a->bonds.type, b->bonds.type, nb * 4))
        return "bond types";
    for (int k = 0; k < MS_TERM_KINDS; k++) {
        const ms_terms *x = &a->terms[k], *y = &b->terms[k];
        if (x->n != y->n || !same_bytes(x->atoms, y->atoms, x->n * ms_term_width(k) * 4) ||
            !x->type != !y->type || !same_bytes(x->type, y->type, x->n * 4))
            return "angles, dihedrals or impropers";
    }
    if (a->nresidues != b->nresidues || a->nfragments != b->nfragments ||
        !same_bytes(a->res_start, b->res_start, (a->nresidues + 1) * 4))
        return "residues or fragments";
    if (a->ss_known != b->ss_known || a->autobonds_pending != b->autobonds_pending ||
        a->active != b->active || a->displayed != b->displayed || a->fixed != b->fixed)
        return "flags";
    for (int k = 0; k < 4; k++)
        if (!a->user[k] != !b->user[k] || !same_bytes(a->user[k], b->user[k], n * 4)) return "user";
    if (!a->pfrag != !b->pfrag || !same_bytes(a->pfrag, b->pfrag, n * 4) ||
        !same_bytes(a->nfrag, b->nfrag, n * 4))
        return "polymer fragments";
    if (memcmp(a->center, b->center, sizeof a->center) || a->scale != b->scale ||
        memcmp(a->rotate, b->rotate, sizeof a->rotate) || memcmp(a->global, b->global, sizeof a->global))
        return "view";
    if (!same_str(a->name, b->name) || !same_str(a->remarks, b->remarks)) return "name or remarks";
    if (a->nfiles != b->nfiles) return "file count";
    for (size_t i = 0; i < a->nfiles; i++)
        if (!same_str(a->files[i].path, b->files[i].path) || !same_str(a->files[i].type, b->files[i].type))
            return "files";
    if (a->nframes != b->nframes || a->frame != b->frame) return "frame count or current frame";
    for (size_t f = 0; f < a->nframes; f++) {
        ms_frame *x = &a->frames[f], *y = &b->frames[f];
        if (!same_bytes(x->pos, y->pos, n * 12) || !x->vel != !y->vel ||
            !same_bytes(x->vel, y->vel, n * 12) || memcmp(x->cell, y->cell, sizeof x->cell) ||
            x->time != y->time || memcmp(x->energy, y->energy, sizeof x->energy)) {
            snprintf(why, sizeof why, "frame %zu", f);
            return why;
        }
    }
    return NULL;
}

/* ---------------------------------------------------------------- the structure */

/* 1tii with every optional part present: 3 frames (the last with velocities), user values,
 * polymer fragments, bond orders and types, a view. */
static ms_molecule *rich_1tii(ms_error *err)
{
    ms_molecule *m = load_err("1tii.pdb", err);
    if (!m) return NULL;
    size_t n = m->atoms.n, nb = m->bonds.start[n];
    for (int k = 1; k <= 2; k++) {
        ms_frame *f = ms_mol_add_frame(m, k == 2, err);
        if (!f) return NULL;
        for (size_t i = 0; i < 3 * n; i++) {
            f->pos[i] = m->frames[0].pos[i] + 0.25f * (float)k;
            if (f->vel) f->vel[i] = (float)(i % 17) * 0.5f;
        }
        f->cell[0] = 10.0f * (float)k;
        f->time = 2.5 * k;
        f->energy[MS_EN_TEMPERATURE] = 300.0f + (float)k;   /* as IMD frames have */
        f->energy[MS_EN_EFIELD] = -(float)k;
    }
    m->frame = 2;
    m->user[1] = ms_alloc_array(n, sizeof(float));
    m->bonds.order = ms_alloc_array(nb, sizeof(float));
    m->bonds.type = ms_alloc_array(nb, sizeof(ms_str));
    if (!m->user[1] || !m->bonds.order || !m->bonds.type || ms_mol_polymer_fragments(m, err))
        return NULL;
    ms_str ar = ms_strtab_intern_cstr(m->strings, "ar");
    for (size_t i = 0; i < n; i++) m->user[1][i] = (float)i * 0.125f;
    for (size_t k = 0; k < nb; k++) {
        m->bonds.order[k] = 1.0f + (float)(k % 3);
        m->bonds.type[k] = k % 5 ? 0 : ar;
    }
    /* Angles untyped, dihedrals typed, no impropers. */
    for (uint32_t i = 0; i + 3 < 200; i++) {
        uint32_t at[4] = {i, i + 1, i + 2, i + 3};
        if (ms_terms_add(m, MS_TERM_ANGLE, at, MS_STR_NONE, err) ||
            ms_terms_add(m, MS_TERM_DIHEDRAL, at, i % 2 ? ar : MS_STR_NONE, err))
            return NULL;
    }
    m->center[1] = 3.5f;
    m->scale = 0.02f;
    m->rotate[1] = 0.5f;
    m->fixed = 1;
    return m;
}

static void test_round_trip(void)
{
    t_suite = "serialize";
    ms_error err = {{0}};
    ms_molecule *m = rich_1tii(&err);
    if (!t_ok(m != NULL, "load 1tii.pdb and add frames, user values, bond orders (%s)", err.msg))
        return;
    void *buf;
    size_t len;
    if (!t_ok(ms_mol_serialize(m, &buf, &len, &err) == 0, "serialise (%s)", err.msg)) return;
    t_ok(len > 5684 * (3 * 12 + 50), "buffer holds 3 frames and the structure (%zu bytes)", len);
    ms_molecule *c = ms_mol_deserialize(buf, len, &err);
    if (t_ok(c != NULL, "deserialise (%s)", err.msg)) {
        const char *d = difference(m, c);
        t_ok(d == NULL, "every array survives the round trip (%s differs)", d ? d : "nothing");
        t_ok(c->atoms.n == 5684 && c->nresidues == 927 && c->nfragments == 222 &&
                 c->bonds.start[c->atoms.n] / 2 == 5575 && c->nframes == 3,
             "copy has 1tii's 5684 atoms, 927 residues, 222 fragments, 5575 bonds, 3 frames");
        t_ok(c->frames[2].vel && !c->frames[1].vel && c->frames[2].time == 5.0,
             "velocities only where they were, times kept");
        t_ok(!strcmp(ms_mol_str(c, c->bonds.type[0]), "ar"), "bond types name the same strings");
        t_ok(c->terms[MS_TERM_ANGLE].n == 197 && !c->terms[MS_TERM_ANGLE].type &&
                 c->terms[MS_TERM_DIHEDRAL].n == 197 &&
                 !strcmp(ms_mol_str(c, c->terms[MS_TERM_DIHEDRAL].type[1]), "ar") &&
                 !strcmp(ms_mol_str(c, c->terms[MS_TERM_DIHEDRAL].type[0]), "") &&
                 c->terms[MS_TERM_IMPROPER].n == 0,
             "197 angles, 197 typed dihedrals, no impropers");
        ms_mol_free(c);
    }
    free(buf);
    ms_mol_free(m);
}

/* Header + blocks, copied block by block as the broadcast does, frames in two batches. */
static void test_blocks(void)
{
    t_suite = "serialize";
    ms_error err = {{0}};
    ms_molecule *m = rich_1tii(&err);
    if (!t_ok(m != NULL, "load (%s)", err.msg)) return;
    ms_molser out, in;
    ms_molecule *c = NULL;
    int ok = ms_molser_pack(m, &out, &err) == 0 &&
             (c = ms_molser_unpack(out.head, out.head_len, &in, &err)) != NULL &&
             in.nblocks == out.nblocks;
    if (!t_ok(ok, "pack and unpack the structure header (%s)", err.msg)) return;
    for (size_t k = 0; k < in.nblocks; k++) {
        ok &= in.block[k].bytes == out.block[k].bytes;
        if (ok) memcpy(in.block[k].data, out.block[k].data, in.block[k].bytes);
    }
    t_ok(ok && ms_molser_finish(c, &in, &err) == 0, "blocks match in size and check (%s)", err.msg);
    ms_molser_free(&out);
    ms_molser_free(&in);
    size_t batches[2][2] = {{0, 1}, {1, 2}};
    for (int b = 0; b < 2; b++) {
        ok = ms_molser_pack_frames(m, batches[b][0], batches[b][1], &out, &err) == 0 &&
             ms_molser_unpack_frames(c, out.head, out.head_len, &in, &err) == 0 &&
             in.nblocks == out.nblocks;
        for (size_t k = 0; ok && k < in.nblocks; k++)
            memcpy(in.block[k].data, out.block[k].data, in.block[k].bytes);
        t_ok(ok, "frame batch %d (%s)", b, err.msg);
        ms_molser_free(&out);
        ms_molser_free(&in);
    }
    const char *d = difference(m, c);
    t_ok(d == NULL, "block by block gives the same molecule (%s differs)", d ? d : "nothing");
    /* Frames of another size are refused and leave the molecule unchanged. */
    ms_molecule *small = load_err("pept.pdb", &err);
    if (small && ms_molser_pack_frames(small, 0, 1, &out, &err) == 0) {
        size_t before = c->nframes;
        t_ok(ms_molser_unpack_frames(c, out.head, out.head_len, &in, &err) == -1 &&
                 c->nframes == before, "frames of a 107-atom molecule refused (%s)", err.msg);
        ms_molser_free(&out);
    }
    ms_mol_free(small);
    ms_mol_free(c);
    ms_mol_free(m);
}

static void test_empty(void)
{
    t_suite = "serialize";
    ms_error err = {{0}};
    ms_molecule *m = ms_mol_new(&err), *c = NULL;
    void *buf = NULL;
    size_t len;
    if (m && ms_mol_serialize(m, &buf, &len, &err) == 0) c = ms_mol_deserialize(buf, len, &err);
    t_ok(c && c->atoms.n == 0 && c->nframes == 0 && c->frame == -1 && !difference(m, c),
         "an empty molecule round-trips (%s)", err.msg);
    free(buf);
    ms_mol_free(c);
    ms_mol_free(m);
}

/* ---------------------------------------------------------------- damage */

static int rejects(ms_molecule *m, const char *expect)
{
    void *buf;
    size_t len;
    ms_error err = {{0}};
    if (ms_mol_serialize(m, &buf, &len, &err)) return 0;
    ms_molecule *c = ms_mol_deserialize(buf, len, &err);
    free(buf);
    ms_mol_free(c);
    return c == NULL && strstr(err.msg, expect) != NULL;
}

static void test_damage(void)
{
    t_suite = "serialize";
    ms_error err = {{0}};
    ms_molecule *m = load_err("pept.pdb", &err);
    if (!t_ok(m != NULL, "load pept.pdb (%s)", err.msg)) return;
    void *buf;
    size_t len;
    if (ms_mol_serialize(m, &buf, &len, &err)) return;
    int all_refused = 1;
    for (size_t cut = 0; cut < len; cut += cut < 400 ? 1 : 97) {
        ms_molecule *c = ms_mol_deserialize(buf, cut, &err);
        if (c) all_refused = 0;
        ms_mol_free(c);
    }
    t_ok(all_refused, "every truncated buffer is refused");
    /* Flip bytes one at a time through the header: an error or a molecule, never a crash. */
    unsigned char *p = buf;
    int survived = 1;
    for (size_t i = 0; i < MS_MIN(len, (size_t)1500); i++) {
        unsigned char keep = p[i];
        p[i] ^= 0x5a;
        ms_molecule *c = ms_mol_deserialize(buf, len, &err);
        if (c && c->atoms.n != m->atoms.n) survived = 0;
        ms_mol_free(c);
        p[i] = keep;
    }
    t_ok(survived, "flipped header bytes give errors or a molecule of the right size");
    free(buf);
    uint32_t keep = m->bonds.to[3];
    m->bonds.to[3] = (uint32_t)m->atoms.n;
    t_ok(rejects(m, "bond table"), "a bond to a missing atom is refused");
    m->bonds.to[3] = keep;
    int32_t r = m->atoms.residue[10];
    m->atoms.residue[10] = (int32_t)m->nresidues;
    t_ok(rejects(m, "residue"), "a residue number out of range is refused");
    m->atoms.residue[10] = r;
    ms_str s = m->atoms.name[4];
    m->atoms.name[4] = ms_strtab_count(m->strings) + 3;
    t_ok(rejects(m, "string"), "a string id out of range is refused");
    m->atoms.name[4] = s;
    t_ok(!rejects(m, ""), "restored, the molecule is accepted again");
    ms_mol_free(m);
}

int main(void)
{
    ms_registry_init(&reg);
    ms_registry_add(&reg, ms_plugin_entry_pdb(), NULL, NULL);
    test_round_trip();
    test_blocks();
    test_empty();
    test_damage();
    ms_registry_free(&reg);
    return t_done();
}
