/* labels.c: VMD's labels (labels.h): the lists per category, their values, their text, and
 * the display list that draws them. */
#include "config.h"
#include "assemble/labels.h"
#include "assemble/view.h"
#include "molecule/elements.h"
#include "vecmath/vecf.h"
#include "select/select.h"
#include "vecmath/vecmath.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const cat_names[MS_LABEL_NCATS] = {"Atoms", "Bonds", "Angles", "Dihedrals"};

const char *ms_label_cat_name(int cat)
{
    return cat >= 0 && cat < MS_LABEL_NCATS ? cat_names[cat] : "";
}

int ms_label_cat_find(const char *word)
{
    for (int i = 0; i < MS_LABEL_NCATS; i++)
        if (ms_word_eq(word, cat_names[i])) return i;
    return -1;
}

void ms_labels_init(ms_labels *L)
{
    memset(L, 0, sizeof *L);
    L->size = 1.0f;
    L->thickness = 1.0f;
}

void ms_labels_free(ms_labels *L)
{
    for (int i = 0; i < MS_LABEL_NCATS; i++) free(L->v[i]);
    ms_labels_init(L);
}

static int same_atoms(const ms_label *a, const ms_label *b)
{
    for (int i = 0; i < a->n; i++)
        if (a->mol[i] != b->mol[i] || a->atom[i] != b->atom[i]) return 0;
    return 1;
}

long ms_labels_add(ms_labels *L, const ms_molset *mols, int cat, const int *mol,
                   const uint32_t *atom, ms_error *err)
{
    ms_label l = {.n = cat + 1, .shown = 1};
    for (int i = 0; i < l.n; i++) {
        const ms_molecule *m = ms_molset_get(mols, mol[i]);
        if (!m) {
            ms_error_set(err, "no molecule %d", mol[i]);
            return -1;
        }
        if (atom[i] >= m->atoms.n) {
            ms_error_set(err, "molecule %d has no atom %u (it has %zu)", mol[i], atom[i], m->atoms.n);
            return -1;
        }
        l.mol[i] = mol[i];
        l.atom[i] = atom[i];
    }
    if (cat == MS_LABEL_ATOMS) snprintf(l.format, sizeof l.format, "%s", MS_LABEL_ATOM_FORMAT);
    for (size_t i = 0; i < L->n[cat]; i++)
        if (same_atoms(&L->v[cat][i], &l)) return (long)i;
    if (ms_grow((void **)&L->v[cat], &L->cap[cat], L->n[cat] + 1, sizeof l)) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    L->v[cat][L->n[cat]] = l;
    return (long)L->n[cat]++;
}

void ms_labels_delete(ms_labels *L, int cat, long i)
{
    if (i < 0) {
        L->n[cat] = 0;
        return;
    }
    if ((size_t)i >= L->n[cat]) return;
    memmove(L->v[cat] + i, L->v[cat] + i + 1, (L->n[cat] - (size_t)i - 1) * sizeof *L->v[cat]);
    L->n[cat]--;
}

void ms_labels_forget_molecule(ms_labels *L, int molid)
{
    for (int c = 0; c < MS_LABEL_NCATS; c++)
        for (size_t i = L->n[c]; i-- > 0;)
            for (int k = 0; k < L->v[c][i].n; k++)
                if (L->v[c][i].mol[k] == molid) {
                    ms_labels_delete(L, c, (long)i);
                    break;
                }
}

/* ---------------------------------------------------------------- values */

/* Atom k of a label at a frame (-1: current), in the molecule's own coordinates. */
static int atom_pos(const ms_molset *mols, const ms_label *l, int k, long frame, double p[3])
{
    const ms_molecule *m = ms_molset_get(mols, l->mol[k]);
    if (!m || l->atom[k] >= m->atoms.n) return -1;
    long f = frame < 0 ? m->frame : frame;
    if (f < 0 || (size_t)f >= m->nframes) return -1;
    ms_error err = {{0}};   /* a streamed frame is read into the window, a cache */
    const ms_frame *fr = ms_mol_frame((ms_molecule *)m, (size_t)f, &err);
    if (!fr) return -1;
    const float *x = fr->pos + 3 * (size_t)l->atom[k];
    for (int i = 0; i < 3; i++) p[i] = x[i];
    return 0;
}

int ms_label_value(const ms_molset *mols, const ms_label *l, long frame, double *value)
{
    double p[4][3], a[3], b[3];
    for (int k = 0; k < l->n; k++)
        if (atom_pos(mols, l, k, frame, p[k])) return -1;
    switch (l->n) {
    case 2: ms_v3_sub(p[1], p[0], a); *value = ms_v3_length(a); break;
    case 3:
        ms_v3_sub(p[0], p[1], a);
        ms_v3_sub(p[2], p[1], b);
        *value = ms_v3_angle(a, b);
        break;
    case 4: *value = ms_v3_dihedral(p[0], p[1], p[2], p[3]); break;
    default: *value = 0.0;
    }
    return 0;
}

long ms_label_frames(const ms_molset *mols, const ms_label *l)
{
    long n = -1;
    for (int k = 0; k < l->n; k++) {
        const ms_molecule *m = ms_molset_get(mols, l->mol[k]);
        long f = m ? (long)m->nframes : 0;
        if (n < 0 || f < n) n = f;
    }
    return n < 0 ? 0 : n;
}

/* ---------------------------------------------------------------- text */

/* One substitution of an atom's format: the text for code c (i1: the "%1i" form); 0 when c
 * is no code. */
static int substitute(const ms_molecule *m, uint32_t i, char c, int i1, char *out, size_t size)
{
    const ms_atoms *a = &m->atoms;
    switch (c) {
    case 'R': snprintf(out, size, "%s", ms_mol_str(m, a->resname[i])); break;
    case 'r': snprintf(out, size, "%c", ms_sel_one_letter(ms_mol_str(m, a->resname[i]), 0)); break;
    case 'd': snprintf(out, size, "%d", (int)a->resid[i]); break;
    case 'a': snprintf(out, size, "%s", ms_mol_str(m, a->name[i])); break;
    case 't': snprintf(out, size, "%s", ms_mol_str(m, a->type[i])); break;
    case 'e': snprintf(out, size, "%s", ms_element_symbol(a->atomicnumber[i])); break;
    case 'q': snprintf(out, size, "%g", (double)a->charge[i]); break;
    case 'b': snprintf(out, size, "%g", (double)a->beta[i]); break;
    case 'o': snprintf(out, size, "%g", (double)a->occupancy[i]); break;
    case 's': snprintf(out, size, "%s", ms_mol_str(m, a->segname[i])); break;
    case 'c': snprintf(out, size, "%s", ms_mol_str(m, a->chain[i])); break;
    case 'i': snprintf(out, size, "%lu", (unsigned long)i + (i1 ? 1u : 0u)); break;
    case '%': snprintf(out, size, "%%"); break;
    default: return 0;
    }
    return 1;
}

static void atom_text(const ms_molecule *m, uint32_t atom, const char *fmt, char *buf, size_t size)
{
    size_t n = 0;
    buf[0] = '\0';
    for (const char *p = fmt; *p && n + 1 < size; p++) {
        char piece[160];
        int i1 = p[0] == '%' && p[1] == '1' && p[2] == 'i';
        if (*p == '%' && substitute(m, atom, i1 ? 'i' : p[1], i1, piece, sizeof piece)) {
            p += i1 ? 2 : 1;
        } else {
            piece[0] = *p;
            piece[1] = '\0';
        }
        size_t k = strlen(piece);
        if (n + k >= size) k = size - 1 - n;
        memcpy(buf + n, piece, k);
        buf[n += k] = '\0';
    }
}

void ms_label_text(const ms_molset *mols, int cat, const ms_label *l, char *buf, size_t size)
{
    double v;
    const ms_molecule *m = ms_molset_get(mols, l->mol[0]);
    if (cat == MS_LABEL_ATOMS && m && l->atom[0] < m->atoms.n)
        atom_text(m, l->atom[0], l->format, buf, size);
    else if (cat != MS_LABEL_ATOMS && ms_label_value(mols, l, -1, &v) == 0)
        snprintf(buf, size, "%.2f", v);
    else
        snprintf(buf, size, "?");
}

/* ---------------------------------------------------------------- drawing */

/* The label's atoms in world coordinates; -1 when one cannot be drawn. */
static int world_atoms(const ms_molset *mols, const ms_label *l, float w[4][3])
{
    for (int k = 0; k < l->n; k++) {
        const ms_molecule *m = ms_molset_get(mols, l->mol[k]);
        double p[3];
        if (!m || !m->displayed || atom_pos(mols, l, k, -1, p)) return -1;
        float model[16], q[3] = {(float)p[0], (float)p[1], (float)p[2]};
        ms_view_mol_model(m, model);
        ms_mat4_point(model, q, w[k]);
    }
    return 0;
}

static int draw_label(const ms_labels *L, const ms_molset *mols, int cat, const ms_label *l,
                      ms_rgba8 col, ms_displaylist *dl)
{
    float w[4][3], anchor[3] = {0, 0, 0};
    if (world_atoms(mols, l, w)) return 0;
    for (int k = 0; k < l->n; k++)
        for (int i = 0; i < 3; i++) anchor[i] += w[k][i] / (float)l->n;
    for (int k = 0; k + 1 < l->n; k++)
        if (ms_dl_line(dl, w[k], w[k + 1], 2.0f * L->thickness, col, MS_LINE_DASHED)) return -1;
    char text[512];
    ms_label_text(mols, cat, l, text, sizeof text);
    anchor[0] += l->offset[0];
    anchor[1] += l->offset[1];
    return ms_dl_text(dl, anchor, text, L->size, L->thickness, col);
}

int ms_labels_to_scene(const ms_labels *L, const ms_molset *mols, const ms_colors *colors,
                       const ms_materials *mats, ms_scene *s, ms_error *err)
{
    static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    size_t any = 0;
    for (int c = 0; c < MS_LABEL_NCATS; c++) any += L->n[c];
    if (!any) return 0;
    ms_displaylist *dl = ms_scene_new_list(s, err);
    if (!dl) return -1;
    dl->lit = 0;
    int cat_labels = ms_color_category_index(colors, "Labels");
    for (int c = 0; c < MS_LABEL_NCATS; c++) {
        int id = ms_color_item_get(colors, cat_labels, cat_names[c]);
        ms_rgba8 col = ms_rgba8_from_float(ms_color_rgb(colors, id < 0 ? 8 : id), 1.0f);
        for (size_t i = 0; i < L->n[c]; i++)
            if (L->v[c][i].shown && draw_label(L, mols, c, &L->v[c][i], col, dl)) {
                ms_error_set(err, "out of memory");
                return -1;
            }
    }
    return ms_scene_add(s, dl, identity, mats, err);
}
