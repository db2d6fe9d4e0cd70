/* fuzz_imd.c: the fuzz target of the IMD message decoder (imd/imd.h). One input is what a
 * simulation might send: byte 0 picks the molecule's atom count (its low 3 bits) and the
 * byte order (bit 3), byte 1 the size of the pieces the bytes arrive in (1 to 256); bytes 2
 * to 9 are checked as a handshake, and everything from byte 2 on is fed to the stream
 * decoder until it refuses a message. Every whole message is checked: coordinates of the
 * molecule's size, nothing refused half-read. Nothing may crash, leak or hang. Built with
 * driver.c as the smoke test tests/fuzz/fuzz_imd, and with libFuzzer by `make fuzz`. */
#include "config.h"
#include "imd/imd.h"

#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Feed data in pieces: the number of whole messages. */
static size_t feed(ms_imd_decoder *d, const uint8_t *data, size_t size, size_t piece)
{
    size_t at = 0, count = 0;
    ms_error err = {{0}};
    while (at < size) {
        size_t n = MS_MIN(piece, size - at), used = 0;
        while (used < n) {
            ms_imd_msg m;
            int done;
            long u = ms_imd_feed(d, data + at + used, n - used, &m, &done, &err);
            if (u < 0) {
                if (!err.msg[0]) abort();          /* a refusal says why */
                return count;
            }
            if (u == 0 && !done) abort();          /* no progress: a hang */
            used += (size_t)u;
            if (done && m.type == MS_IMD_FCOORDS) {
                volatile float sum = 0;
                if ((size_t)m.length != d->natoms) abort();
                for (size_t i = 0; i < 3 * d->natoms; i++) sum += m.coords[i];
                (void)sum;
            }
            count += (size_t)done;
        }
        at += n;
    }
    return count;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 2) return 0;
    size_t natoms = data[0] & 7u, piece = (size_t)data[1] + 1;
    int swap = (data[0] >> 3) & 1;
    ms_error err = {{0}};
    if (size >= 10) {
        int hs;
        if (ms_imd_check_handshake(data + 2, &hs, &err) == 0 && hs != 0 && hs != 1) abort();
    }
    ms_imd_decoder d;
    if (ms_imd_decoder_init(&d, natoms, swap, &err)) return 0;
    feed(&d, data + 2, size - 2, piece);
    ms_imd_decoder_free(&d);
    return 0;
}
