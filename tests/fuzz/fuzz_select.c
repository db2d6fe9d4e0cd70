/* fuzz_select.c: the fuzz target of the selection language. One input is a selection text:
 * it is compiled, and when it compiles it is evaluated on a small molecule built here (two
 * protein-like residues, a water, bonds, a periodic cell), on its frame and past its end;
 * it is also tried as a macro definition. Nothing may crash, leak or hang. Entry point in
 * libFuzzer's form, so the same file serves the smoke driver (select_driver.c) and
 * `clang -fsanitize=fuzzer`. */
#include "config.h"
#include "molecule/analysis.h"
#include "select/select.h"

#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static ms_molecule *fuzz_molecule(void)
{
    static const char *names[] = {"N", "CA", "C", "O", "CB", "SG", "N", "CA", "C", "O", "CB",
                                  "OT1", "OH2", "H1", "H2", "C5'", "1HB", "NA"};
    static const char *resnames[] = {"CYS", "CYS", "CYS", "CYS", "CYS", "CYS", "ALA", "ALA",
                                     "ALA", "ALA", "ALA", "ALA", "HOH", "HOH", "HOH", "ADE",
                                     "ADE", "NA"};
    ms_error err = {{0}};
    ms_molecule *m = ms_mol_new(&err);
    size_t n = sizeof names / sizeof names[0];
    for (size_t i = 0; m && i < n; i++) {
        if (ms_mol_add_blank_atom(m, &err) < 0) return m;
        m->atoms.name[i] = ms_strtab_intern_cstr(m->strings, names[i]);
        m->atoms.resname[i] = ms_strtab_intern_cstr(m->strings, resnames[i]);
        m->atoms.chain[i] = ms_strtab_intern_cstr(m->strings, i < 12 ? "A" : "W");
        m->atoms.resid[i] = i < 6 ? 1 : i < 12 ? 2 : i < 15 ? 3 : (int)i;
        m->atoms.beta[i] = (float)i;
        m->atoms.altloc[i] = i % 5 == 0 ? 'A' : '\0';
        ms_analysis_atom_defaults(m, i, 0, 0, 0);
    }
    ms_frame *f = ms_mol_add_frame(m, 1, &err);
    for (size_t i = 0; f && i < 3 * n; i++) {
        f->pos[i] = (float)((i * 7919) % 23) * 0.7f - 5;
        f->vel[i] = (float)i;
    }
    if (f) {
        const float cell[6] = {12, 13, 14, 80, 95, 110};
        memcpy(f->cell, cell, sizeof cell);
        m->frame = 0;
    }
    static const uint32_t pairs[] = {0, 1, 1, 2, 2, 3, 1, 4, 4, 5, 2, 6, 6, 7, 7, 8, 8, 9,
                                     7, 10, 8, 11, 12, 13, 12, 14, 15, 16, 5, 10};
    ms_mol_set_bonds(m, sizeof pairs / sizeof pairs[0] / 2, pairs, NULL, &err);
    return m;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static ms_molecule *m;
    if (!m) m = fuzz_molecule();
    char *text = malloc(size + 1);
    if (!text || !m) {
        free(text);
        return 0;
    }
    memcpy(text, data, size);
    text[size] = '\0';
    ms_error err = {{0}};
    ms_selexpr *e = ms_sel_compile(text, &err);
    if (e) {
        static const long frames[] = {-1, -2, 0, 5};
        for (size_t k = 0; k < sizeof frames / sizeof frames[0]; k++) {
            ms_bitset b;
            if (ms_sel_eval(e, m, frames[k], &b, &err) == 0) ms_bitset_free(&b);
        }
        ms_sel_free(e);
        if (ms_sel_macro_define("fuzz_macro", text, &err) == 0) {
            ms_bitset b;
            if (ms_sel_select(m, -1, "fuzz_macro or not fuzz_macro", &b, &err) == 0)
                ms_bitset_free(&b);
            ms_sel_macro_delete("fuzz_macro", &err);
        }
    }
    free(text);
    return 0;
}
