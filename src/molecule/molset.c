/* molset.c: the molecule list, top molecule and event fan-out. */
#include "config.h"
#include "molecule/molset.h"

#include <stdlib.h>
#include <string.h>

void ms_molset_init(ms_molset *s)
{
    memset(s, 0, sizeof *s);
    s->top = -1;
}

static void molset_free_one(ms_molset *s, ms_molecule *m)
{
    for (int k = 0; k < s->next_ext; k++)
        if (m->ext[k] && s->ext_free[k]) s->ext_free[k](m->ext[k]);
    ms_mol_free(m);
}

void ms_molset_free(ms_molset *s)
{
    for (size_t i = 0; i < s->n; i++) molset_free_one(s, s->mols[i]);
    free(s->mols);
    ms_molset_init(s);
}

int ms_molset_add(ms_molset *s, ms_molecule *m, ms_error *err)
{
    if (ms_grow((void **)&s->mols, &s->cap, s->n + 1, sizeof *s->mols)) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    m->id = s->next_id++;
    s->mols[s->n++] = m;
    s->top = m->id;
    ms_molset_emit(s, MS_EV_MOL_NEW, m, NULL);
    return 0;
}

int ms_molset_index_of(const ms_molset *s, int id)
{
    for (size_t i = 0; i < s->n; i++)
        if (s->mols[i]->id == id) return (int)i;
    return -1;
}

ms_molecule *ms_molset_get(const ms_molset *s, int id)
{
    int i = ms_molset_index_of(s, id);
    return i < 0 ? NULL : s->mols[i];
}

ms_molecule *ms_molset_top(const ms_molset *s)
{
    return s->top < 0 ? NULL : ms_molset_get(s, s->top);
}

void ms_molset_delete(ms_molset *s, int id)
{
    int i = ms_molset_index_of(s, id);
    if (i < 0) return;
    ms_molecule *m = s->mols[i];
    ms_molset_emit(s, MS_EV_MOL_DELETE, m, NULL);
    memmove(s->mols + i, s->mols + i + 1, (s->n - (size_t)i - 1) * sizeof *s->mols);
    s->n--;
    /* VMD makes the most recently loaded remaining molecule top. */
    if (s->top == id) s->top = s->n ? s->mols[s->n - 1]->id : -1;
    molset_free_one(s, m);
}

int ms_molset_goto(ms_molset *s, ms_molecule *m, long frame, ms_error *err)
{
    if (m->nframes == 0) {
        m->frame = -1;
        return 0;
    }
    if (frame < 0) frame = 0;
    if (frame >= (long)m->nframes) frame = (long)m->nframes - 1;
    if (ms_mol_goto(m, (size_t)frame, err)) return -1;
    ms_molset_emit(s, MS_EV_FRAME, m, NULL);
    return 0;
}

void ms_molset_set_frame(ms_molset *s, ms_molecule *m, long frame)
{
    ms_error err = {{0}};
    ms_molset_goto(s, m, frame, &err);
}

void ms_molset_emit(ms_molset *s, ms_mol_event ev, ms_molecule *m, const char *arg)
{
    int id = m ? m->id : -1, in_set = m && ms_molset_get(s, id) == m;
    for (int i = 0; i < s->nlisteners; i++) {
        s->listeners[i].fn(s->listeners[i].ud, ev, m, arg);
        /* a listener (a Tcl trace callback) may have deleted the molecule: the others
         * must not see it */
        if (in_set && ms_molset_get(s, id) != m) return;
    }
}

int ms_molset_listen(ms_molset *s, ms_mol_listener fn, void *ud)
{
    if (s->nlisteners >= MS_MAX_LISTENERS) return -1;
    s->listeners[s->nlisteners].fn = fn;
    s->listeners[s->nlisteners].ud = ud;
    s->nlisteners++;
    return 0;
}

int ms_molset_register_ext(ms_molset *s, ms_ext_free_fn free_fn)
{
    if (s->next_ext >= MS_MAX_EXT) return -1;
    s->ext_free[s->next_ext] = free_fn;
    return s->next_ext++;
}
