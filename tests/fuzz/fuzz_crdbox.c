/* fuzz_crdbox.c: the fuzz target of AMBER's ASCII trajectory reader and writer (type crdbox):
 * the input is added to a molecule of 5 atoms, the count the seeds are made for, as the
 * file gives none (see fuzz.h). Built with driver.c as the smoke test tests/fuzz/fuzz_crdbox,
 * and with libFuzzer by `make fuzz`. */
#include "fuzz.h"

const ms_plugin *ms_plugin_entry(void);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return ms_fuzz_load_frames(ms_plugin_entry(), 5, data, size);
}
