/* comm.c: the MPI layer: start-up (only under a launcher), the job's shape, shutdown and
 * abort, and collectives on byte buffers. Without MPI every call is the one-rank case. */
#include "config.h"
#include "parallel/parallel.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "parallel/internal.h"

#define NAME_LEN 256
#ifdef MS_HAVE_MPI
_Static_assert(NAME_LEN >= MPI_MAX_PROCESSOR_NAME, "room for MPI's processor name");
#endif

/* Broadcasts go in pieces of this size: MPI counts are ints, and pieces let large
 * messages stream through the network while the next one is prepared. */
#define PIECE ((size_t)64 << 20)

static struct {
    int inited;        /* ms_par_init ran */
    int mpi;           /* MPI in use */
    int owner;         /* this copy called MPI_Init (and will finalize) */
    int finalized;
    int rank, size, local_size, thread_level;
    char name[NAME_LEN];
#ifdef MS_HAVE_MPI
    MPI_Comm comm;     /* our duplicate of MPI_COMM_WORLD */
#endif
} par = {.size = 1, .local_size = 1};

static void set_host_name(void)
{
    if (gethostname(par.name, sizeof par.name - 1) != 0) strcpy(par.name, "localhost");
    par.name[sizeof par.name - 1] = '\0';
}

#ifdef MS_HAVE_MPI
/* Environment variables that launchers set in the processes they start. */
static int under_launcher(void)
{
    static const char *vars[] = {
        "OMPI_COMM_WORLD_SIZE",  /* OpenMPI mpirun */
        "PMIX_RANK",             /* PMIx launchers: OpenMPI 5 prterun, srun --mpi=pmix */
        "PMI_RANK", "PMI_SIZE", "PMI_FD", /* MPICH Hydra, Intel MPI, srun --mpi=pmi2 */
        "MPI_LOCALNRANKS",       /* MPICH Hydra */
        "MV2_COMM_WORLD_SIZE",   /* MVAPICH mpirun_rsh */
        "ALPS_APP_PE",           /* Cray aprun */
    };
    if (ms_env_flag("MOLSCOPE_MPI")) return 1;
    for (size_t i = 0; i < MS_COUNTOF(vars); i++)
        if (getenv(vars[i])) return 1;
    return 0;
}

static int mpi_start(int *argc, char ***argv, ms_error *err)
{
    int flag = 0, fin = 0;
    MPI_Finalized(&fin);
    if (fin) {
        ms_error_set(err, "MPI was already finalized");
        return -1;
    }
    MPI_Initialized(&flag);
    if (!flag) {
        if (!under_launcher()) return 0;
        if (MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &par.thread_level) !=
            MPI_SUCCESS) {
            ms_error_set(err, "MPI_Init_thread failed");
            return -1;
        }
        par.owner = 1;
    } else {
        MPI_Query_thread(&par.thread_level);
    }
    MPI_Comm_dup(MPI_COMM_WORLD, &par.comm);
    MPI_Comm_rank(par.comm, &par.rank);
    MPI_Comm_size(par.comm, &par.size);
    MPI_Comm local;
    if (MPI_Comm_split_type(par.comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local) ==
        MPI_SUCCESS) {
        MPI_Comm_size(local, &par.local_size);
        MPI_Comm_free(&local);
    }
    int len = 0;
    if (MPI_Get_processor_name(par.name, &len) != MPI_SUCCESS || len <= 0) set_host_name();
    par.mpi = 1;
    return 0;
}
#endif

int ms_par_init(int *argc, char ***argv, ms_error *err)
{
    if (par.inited) return 0;
    par.inited = 1;
    set_host_name();
    if (ms_env_flag("MOLSCOPE_NOMPI")) return 0;
#ifdef MS_HAVE_MPI
    return mpi_start(argc, argv, err);
#else
    (void)argc;
    (void)argv;
    (void)err;
    return 0;
#endif
}

int ms_par_using_mpi(void) { return par.mpi; }
int ms_par_owner(void) { return par.owner; }
int ms_par_rank(void) { return par.rank; }
int ms_par_size(void) { return par.size; }
int ms_par_local_size(void) { return par.local_size; }
int ms_par_thread_level(void) { return par.thread_level; }

const char *ms_par_nodename(void)
{
    if (!par.name[0]) set_host_name();
    return par.name;
}

int ms_par_exit(int status)
{
#ifdef MS_HAVE_MPI
    if (!par.mpi || par.finalized) return status;
    if (status != 0 && par.size > 1) {
        fflush(stdout);
        fprintf(stderr, "molscope: rank %d: exit status %d: ending the job\n", par.rank, status);
        fflush(stderr);
        MPI_Abort(MPI_COMM_WORLD, status);
    }
    par.finalized = 1;
    MPI_Comm_free(&par.comm);
    if (par.owner) MPI_Finalize();
#endif
    return status;
}

void ms_par_abort(int status, const char *fmt, ...)
{
    va_list ap;
    fflush(stdout);
    fprintf(stderr, "molscope: rank %d: ", par.rank);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    fflush(stderr);
    if (status == 0) status = 1;
#ifdef MS_HAVE_MPI
    if (par.mpi && !par.finalized && par.size > 1) MPI_Abort(MPI_COMM_WORLD, status);
#endif
    exit(status);
}

/* ---------------------------------------------------------------- collectives */

void ms_par_backoff(int *spins)
{
    if (++*spins < 100) return;
    long ns = *spins < 1000 ? 50000L : 2000000L;
    struct timespec ts = {0, ns};
    nanosleep(&ts, NULL);
}

#ifdef MS_HAVE_MPI
MPI_Comm ms_par_comm(void) { return par.comm; }

int ms_par_wait(MPI_Request *req, double timeout)
{
    double t0 = timeout > 0 ? ms_now() : 0;
    int done = 0, spins = 0;
    for (;;) {
        MPI_Test(req, &done, MPI_STATUS_IGNORE);
        if (done) return 0;
        if (timeout > 0 && ms_now() - t0 > timeout) return -1;
        ms_par_backoff(&spins);
    }
}
#endif

int ms_par_barrier(ms_error *err)
{
    (void)err;
#ifdef MS_HAVE_MPI
    if (par.mpi && par.size > 1) {
        MPI_Request req;
        MPI_Ibarrier(par.comm, &req);
        ms_par_wait(&req, 0);
    }
#endif
    return 0;
}

int ms_par_bcast(void *buf, size_t bytes, ms_error *err)
{
    (void)err;
#ifdef MS_HAVE_MPI
    if (!par.mpi || par.size == 1) return 0;
    for (size_t off = 0; off < bytes; off += PIECE) {
        size_t n = MS_MIN(PIECE, bytes - off);
        MPI_Bcast((char *)buf + off, (int)n, MPI_BYTE, 0, par.comm);
    }
#else
    (void)buf;
    (void)bytes;
#endif
    return 0;
}

int ms_par_bcast_small(void *buf, size_t bytes, ms_error *err)
{
#ifdef MS_HAVE_MPI
    if (par.mpi && par.size > 1 && bytes <= INT_MAX) {
        MPI_Request req;
        MPI_Ibcast(buf, (int)bytes, MPI_BYTE, 0, par.comm, &req);
        ms_par_wait(&req, 0);
        return 0;
    }
#endif
    return ms_par_bcast(buf, bytes, err);
}

int ms_par_bcast_buffer(void **buf, size_t *len, ms_error *err)
{
    if (par.size == 1) return 0;
    uint64_t n = par.rank == 0 ? (uint64_t)*len : 0;
    if (ms_par_bcast(&n, sizeof n, err)) return -1;
    if (par.rank != 0) {
        if (n > SIZE_MAX - 1 || !(*buf = malloc(n ? (size_t)n : 1))) {
            /* Every rank must take part in the broadcast that follows: end the job. */
            ms_par_abort(1, "out of memory for a broadcast of %llu bytes",
                         (unsigned long long)n);
        }
        *len = (size_t)n;
    }
    return ms_par_bcast(*buf, (size_t)n, err);
}

void ms_par_parts_free(ms_par_parts *p)
{
    free(p->data);
    free(p->off);
    free(p->len);
    memset(p, 0, sizeof *p);
}

/* One rank: its own bytes are the only part. */
static int parts_self(const void *buf, size_t len, ms_par_parts *out, ms_error *err)
{
    memset(out, 0, sizeof *out);
    out->data = malloc(len ? len : 1);
    out->off = calloc(1, sizeof *out->off);
    out->len = calloc(1, sizeof *out->len);
    if (!out->data || !out->off || !out->len) {
        ms_par_parts_free(out);
        ms_error_set(err, "out of memory");
        return -1;
    }
    memcpy(out->data, buf, len);
    out->len[0] = len;
    out->n = 1;
    return 0;
}

#ifdef MS_HAVE_MPI
/* Gather (root >= 0: to that rank only) or allgather (root < 0) variable-length bytes. */
static int gather_v(const void *buf, size_t len, int root, ms_par_parts *out, ms_error *err)
{
    int n = par.size, me = root < 0 || par.rank == root;
    if (len > INT_MAX) {
        /* Every rank must still take part: send a length that says "too big". */
        len = (size_t)INT_MAX + 1;
    }
    long long mine = (long long)len, *all = malloc((size_t)n * sizeof *all);
    int *counts = malloc((size_t)n * sizeof *counts), *displs = malloc((size_t)n * sizeof *displs);
    if (!all || !counts || !displs) ms_par_abort(1, "out of memory gathering from %d ranks", n);
    /* Ranks arrive here at different times: wait for the lengths without spinning. */
    MPI_Request req;
    MPI_Iallgather(&mine, 1, MPI_LONG_LONG, all, 1, MPI_LONG_LONG, par.comm, &req);
    ms_par_wait(&req, 0);
    long long total = 0;
    for (int r = 0; r < n; r++) total += all[r];
    int too_big = total > INT_MAX;
    memset(out, 0, sizeof *out);
    if (!too_big) {
        for (int r = 0, off = 0; r < n; r++) {
            counts[r] = (int)all[r];
            displs[r] = off;
            off += counts[r];
        }
        char *data = me ? malloc(total ? (size_t)total : 1) : NULL;
        if (me && !data) ms_par_abort(1, "out of memory gathering %lld bytes", total);
        if (root < 0)
            MPI_Allgatherv(buf, (int)len, MPI_BYTE, data, counts, displs, MPI_BYTE, par.comm);
        else
            MPI_Gatherv(buf, (int)len, MPI_BYTE, data, counts, displs, MPI_BYTE, root, par.comm);
        if (me) {
            out->data = data;
            out->off = malloc((size_t)n * sizeof *out->off);
            out->len = malloc((size_t)n * sizeof *out->len);
            if (!out->off || !out->len) ms_par_abort(1, "out of memory");
            for (int r = 0; r < n; r++) {
                out->off[r] = (size_t)displs[r];
                out->len[r] = (size_t)counts[r];
            }
            out->n = n;
        }
    }
    free(all);
    free(counts);
    free(displs);
    if (too_big) {
        ms_error_set(err, "the values of all ranks together exceed 2 GiB (%lld bytes)", total);
        return -1;
    }
    return 0;
}
#endif

int ms_par_allgather(const void *buf, size_t len, ms_par_parts *out, ms_error *err)
{
#ifdef MS_HAVE_MPI
    if (par.mpi && par.size > 1) return gather_v(buf, len, -1, out, err);
#endif
    return parts_self(buf, len, out, err);
}

int ms_par_gather0(const void *buf, size_t len, ms_par_parts *out, ms_error *err)
{
#ifdef MS_HAVE_MPI
    if (par.mpi && par.size > 1) return gather_v(buf, len, 0, out, err);
#endif
    return parts_self(buf, len, out, err);
}

int ms_par_agree(uint64_t key, double timeout, int *same, ms_error *err)
{
    *same = 1;
#ifdef MS_HAVE_MPI
    if (!par.mpi || par.size == 1) return 0;
    /* The minimum of (key, ~key) gives the smallest and the largest key at once. */
    uint64_t mine[2] = {key, ~key}, all[2];
    MPI_Request req;
    MPI_Iallreduce(mine, all, 2, MPI_UINT64_T, MPI_MIN, par.comm, &req);
    if (ms_par_wait(&req, timeout)) {
        ms_error_set(err, "not every rank arrived within %g s", timeout);
        return -1;
    }
    *same = all[0] == ~all[1]; /* the smallest key is the largest: all equal */
#else
    (void)key;
    (void)timeout;
    (void)err;
#endif
    return 0;
}

