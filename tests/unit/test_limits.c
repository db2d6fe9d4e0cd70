/* test_limits.c: every reader checks the sizes a header declares (grid points, atom, bond
 * and value counts) against what the file can hold before anything is allocated for them:
 * a file of a few hundred bytes whose header claims billions of points or atoms is refused
 * at once, with an error that names the numbers, and the process never reserves the memory
 * (its peak virtual size stays put). Also: a biological assembly too large for memory is
 * refused before its atoms are copied. Every plugin is linked in. */
#include "config.h"
#include "builtin/builtin.h"
#include "ms_test.h"
#include "fileio/assembly.h"
#include "fileio/load.h"

#include <stdint.h>
#include <string.h>
#include <unistd.h>

static ms_registry reg;

/* Peak virtual size of this process (VmPeak), in bytes; 0 when unknown. */
static size_t vm_peak(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    unsigned long long kb = 0;
    while (f && fgets(line, sizeof line, f))
        if (sscanf(line, "VmPeak: %llu kB", &kb) == 1) break;
    if (f) fclose(f);
    return (size_t)kb * 1024u;
}

static const char *scratch(const char *ext)
{
    static char path[4096];
    const char *dir = getenv("MS_TEST_OUT");
    snprintf(path, sizeof path, "%s/limits_%ld.%s", dir ? dir : "/tmp", (long)getpid(), ext);
    return path;
}

static const char *write_bytes(const char *ext, const void *data, size_t n)
{
    const char *path = scratch(ext);
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(data, 1, n, f);
        fclose(f);
    }
    return path;
}

static const char *write_text(const char *ext, const char *text)
{
    return write_bytes(ext, text, strlen(text));
}

static void put_be(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24), p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8), p[3] = (unsigned char)v;
}

static void put_le(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)v, p[1] = (unsigned char)(v >> 8);
    p[2] = (unsigned char)(v >> 16), p[3] = (unsigned char)(v >> 24);
}

/* Load path; it must fail within a second with an error containing every string of want
 * (up to three, NULL-terminated). */
static void refused(const char *name, const char *path, const char *const want[])
{
    ms_load_opts o;
    ms_load_opts_default(&o);
    o.waitfor = -1;
    ms_error err = {{0}};
    double t0 = ms_now();
    ms_molecule *m = ms_load_new(&reg, path, &o, &err);
    double dt = ms_now() - t0;
    int ok = !m && dt < 1.0;
    for (int k = 0; want[k]; k++) ok = ok && strstr(err.msg, want[k]);
    t_ok(ok, "%s: refused in %.3f s (%s)", name, dt, m ? "it loaded" : err.msg);
    ms_mol_free(m);
}

#define WANT(...) ((const char *const[]){__VA_ARGS__, NULL})

static void text_formats(void)
{
    refused("DX: 4000^3 points in 300 bytes",
            write_text("dx", "object 1 class gridpositions counts 4000 4000 4000\n"
                              "origin 0 0 0\ndelta 1 0 0\ndelta 0 1 0\ndelta 0 0 1\n"
                              "object 2 class gridconnections counts 4000 4000 4000\n"
                              "object 3 class array type double rank 0 items 64000000000 "
                              "data follows\n1 2 3\n"),
            WANT("line 1: the header declares 4000 x 4000 x 4000 points but the file holds "
                 "only 6 bytes after it (room for at most 3 values)"));
    static const char cube[] =
        "huge\ngrid\n    1    0.0    0.0    0.0\n 4000    0.1    0.0    0.0\n"
        " 4000    0.0    0.1    0.0\n 4000    0.0    0.0    0.1\n"
        "    8    8.0    1.0    2.0    3.0\n1.0 2.0 3.0\n";
    refused("cube: 4000^3 points", write_text("cube", cube),
            WANT("lines 4-6: the header declares 4000 x 4000 x 4000 points but the file holds "
                 "only 12 bytes after it"));
    static const char cube_atoms[] =
        "huge\natoms\n 90000000    0.0    0.0    0.0\n 2    0.1    0.0    0.0\n"
        " 2    0.0    0.1    0.0\n 2    0.0    0.0    0.1\n    8    8.0    1.0    2.0    3.0\n";
    refused("cube: 90000000 atoms", write_text("cube", cube_atoms),
            WANT("line 3: the header declares 90000000 atoms but the file holds only"));
    static const char psf[] = "PSF\n\n       1 !NTITLE\n REMARKS x\n\n 1000000000 !NATOM\n"
                              "       1 U    1    GLY  N    NH3   -0.300000       14.0070           0\n";
    refused("PSF: 10^9 atoms", write_text("psf", psf),
            WANT("line 6: !NATOM declares 1000000000 atoms but the file holds only 71 bytes"));
    static const char psf_bonds[] = "PSF\n\n       1 !NTITLE\n REMARKS x\n\n       2 !NATOM\n"
                                    "       1 U    1    GLY  N    NH3   -0.300000       14.0070           0\n"
                                    "       2 U    1    GLY  CA   CT1    0.210000       12.0110           0\n"
                                    "\n 500000000 !NBOND: bonds\n       1       2\n";
    refused("PSF: 5 10^8 bonds", write_text("psf", psf_bonds),
            WANT("line 10: !NBOND declares 500000000 bonds but the file holds only 17 bytes"));
    static const char gro[] = "huge\n1000000000\n    1GLY      N    1   0.000   0.000   0.000\n"
                              "   1.0   1.0   1.0\n";
    refused("GRO: 10^9 atoms", write_text("gro", gro),
            WANT("line 2: the header declares 1000000000 atoms but the file holds only"));
    static const char xyz[] = "1000000000\ncomment\nC 0 0 0\n";
    refused("XYZ: 10^9 atoms", write_text("xyz", xyz),
            WANT("line 1: the header declares 1000000000 atoms but the file holds only 8 bytes"));
    static const char mol2[] = "@<TRIPOS>MOLECULE\nhuge\n 1000000000 0 1\nSMALL\nNO_CHARGES\n\n"
                               "@<TRIPOS>ATOM\n 1 C1 0.0 0.0 0.0 C.3 1 LIG 0.0\n";
    refused("MOL2: 10^9 atoms", write_text("mol2", mol2),
            WANT("line 3: the MOLECULE record declares 1000000000 atoms"));
}

/* A DCD header (CHARMM, little-endian, 32-bit markers) for natoms, then extra bytes. */
static size_t dcd_header(unsigned char *b, int32_t natoms)
{
    size_t o = 0;
    put_le(b + o, 84), o += 4;
    memcpy(b + o, "CORD", 4), o += 4;
    memset(b + o, 0, 80);
    put_le(b + o, 1);           /* frames */
    put_le(b + o + 76, 24);     /* CHARMM version */
    o += 80;
    put_le(b + o, 84), o += 4;
    put_le(b + o, 84), o += 4;  /* title record: one 80-character line */
    put_le(b + o, 1), o += 4;
    memset(b + o, ' ', 80), o += 80;
    put_le(b + o, 84), o += 4;
    put_le(b + o, 4), o += 4;
    put_le(b + o, (uint32_t)natoms), o += 4;
    put_le(b + o, 4), o += 4;
    return o;
}

/* A TRR frame header with a box and no coordinates, for natoms. */
static size_t trr_header(unsigned char *b, int32_t natoms)
{
    size_t o = 0;
    put_be(b + o, 1993), o += 4;
    put_be(b + o, 13), o += 4;
    put_be(b + o, 12), o += 4;
    memcpy(b + o, "GMX_trn_file", 12), o += 12;
    int32_t s[13] = {0, 0, 36, 0, 0, 0, 0, 0, 0, 0, natoms, 0, 0};
    for (int k = 0; k < 13; k++) put_be(b + o, (uint32_t)s[k]), o += 4;
    memset(b + o, 0, 8 + 36), o += 8 + 36;   /* time, lambda, box */
    return o;
}

static void binary_formats(void)
{
    unsigned char b[2048];
    memset(b, 0, sizeof b);
    size_t n = dcd_header(b, 2000000000);
    refused("DCD: 2 10^9 atoms and no frame", write_bytes("dcd", b, n),
            WANT("header:", "2000000000 atoms", "no frame"));
    n = dcd_header(b, 2000000000);
    refused("DCD: 2 10^9 atoms and 400 bytes of frame", write_bytes("dcd", b, n + 400),
            WANT("frame 0: truncated", "2000000000 atoms"));
    memset(b, 0, sizeof b);
    put_be(b, 1995), put_be(b + 4, 2000000000), put_be(b + 52, 2000000000);
    refused("XTC: 2 10^9 atoms in 100 bytes", write_bytes("xtc", b, 100),
            WANT("frame 0: the header declares 2000000000 atoms, more than the file's 100 bytes"));
    memset(b, 0, sizeof b);
    n = trr_header(b, 20000000);
    refused("TRR: 2 10^7 atoms, a box and no positions", write_bytes("trr", b, n),
            WANT("frame 0: the header declares 20000000 atoms", "file's 120 bytes"));
    memset(b, 0, sizeof b);
    put_le(b, 1000000000);
    refused("NAMD binary: 10^9 atoms in 28 bytes", write_bytes("coor", b, 28),
            WANT("28 bytes do not hold the 1000000000 atoms"));
    memset(b, 0, sizeof b);
    put_le(b, 4000), put_le(b + 4, 4000), put_le(b + 8, 4000), put_le(b + 12, 2);
    for (int k = 0; k < 3; k++) put_le(b + 64 + 4 * k, (uint32_t)(k + 1));
    refused("CCP4: 4000^3 points in 1100 bytes", write_bytes("ccp4", b, 1100),
            WANT("header: declares 4000 x 4000 x 4000 points of 4 bytes (mode 2)",
                 "holds only 1100"));
}

/* An assembly of 2^40 atoms (one operator over a range the size of a huge file) needs far
 * more memory than any machine has: refused by the plan, before a copy is made. */
static void huge_assembly(void)
{
    t_suite = "assembly";
    ms_asm_plan all = {0}, sel;
    size_t range[1][2] = {{0, (size_t)1 << 40}};
    double op[1][12] = {{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0}};
    ms_error err = {{0}};
    if (ms_asm_plan_add(&all, "1", 1, (const size_t(*)[2])range, 1, (const double(*)[12])op,
                        &err)) {
        t_ok(0, "plan an assembly (%s)", err.msg);
        return;
    }
    int rc = ms_asm_select(&all, "1", (size_t)1 << 40, &sel, &err);
    t_ok(rc < 0 && strstr(err.msg, "assembly '1' has 1099511627776 atoms") &&
             strstr(err.msg, "memory available"),
         "an assembly larger than memory is refused (%s)", err.msg);
    if (rc == 0) ms_asm_plan_free(&sel);
    ms_asm_plan_free(&all);
}

int main(void)
{
    ms_registry_init(&reg);
    if (ms_test_add_builtin(&reg)) return 1;
    size_t peak0 = vm_peak();
    t_suite = "limits";
    text_formats();
    binary_formats();
    size_t peak1 = vm_peak();
    t_ok(peak0 && peak1 - peak0 < ((size_t)256 << 20),
         "no reader reserved memory for what its header declared (peak virtual size grew "
         "%.0f MB)", (double)(peak1 - peak0) / 1048576);
    huge_assembly();
    unlink(scratch("dx")), unlink(scratch("cube")), unlink(scratch("psf"));
    unlink(scratch("gro")), unlink(scratch("xyz")), unlink(scratch("mol2"));
    unlink(scratch("dcd")), unlink(scratch("xtc")), unlink(scratch("trr"));
    unlink(scratch("coor")), unlink(scratch("ccp4"));
    ms_registry_free(&reg);
    return t_done();
}
