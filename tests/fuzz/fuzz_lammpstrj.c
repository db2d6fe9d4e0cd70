/* fuzz_lammpstrj.c: the fuzz target of the LAMMPS dump reader (and writer): see fuzz.h.
 * Built with driver.c as the smoke test tests/fuzz/fuzz_lammpstrj, and with libFuzzer by
 * `make fuzz`. */
#include "fuzz.h"

const ms_plugin *ms_plugin_entry(void);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return ms_fuzz_load(ms_plugin_entry(), data, size);
}
