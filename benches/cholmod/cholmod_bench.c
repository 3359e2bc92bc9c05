/* CHOLMOD as the reference for ecc's sparse Cholesky factorisation (issue #11).
 *
 *   cholmod_bench FILE.mtx [--repeats R] [--threads 1,2] [--ordering metis|amd]...
 *
 * Reads a symmetric Matrix Market file (lower triangle, as written by
 * `export_hessians`), and for each ordering (default: metis, then amd):
 * cholmod_analyze once (nmethods = 1, method[0].ordering = CHOLMOD_METIS or
 * CHOLMOD_AMD, postordered, supernodal forced), two untimed warm-up
 * factorisations, then R rounds (default 5) of one timed numeric
 * cholmod_factorize per thread count, the thread counts taking turns so the
 * load of a shared machine hits them alike. The thread count is set in
 * process for OpenBLAS (openblas_set_num_threads) and OpenMP
 * (omp_set_num_threads). CHOLMOD 3.0's own OpenMP loops (copying A into the
 * supernodes) ask for CHOLMOD_OMP_NUM_THREADS = 4 threads regardless, so
 * run.sh starts one process per thread count with OMP_THREAD_LIMIT and
 * OPENBLAS_NUM_THREADS set to it: then T threads really means at most T.
 *
 * Prints one JSON line per (ordering, threads), the shape of
 * `factor_bench` (benches/src/bin/factor_bench.rs): nnz(L) = Common->lnz,
 * flops = Common->fl (sum of squared column counts of L), best and mean
 * factorisation seconds, the seconds of one solve with two right-hand sides
 * (solve2_s: u and v, as the Tutte system has), the 1-minute load average.
 * Exit status 1 on any failure (unreadable file, not positive definite, out
 * of memory). */
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <suitesparse/cholmod.h>

extern void openblas_set_num_threads(int);

#define MAX_THREADS 8
#define MAX_ORDERINGS 4
#define MAX_REPEATS 1000

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double load1(void) {
    double l = -1.0;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf", &l) != 1) l = -1.0;
        fclose(f);
    }
    return l;
}

static void die(const char *what) {
    fprintf(stderr, "cholmod_bench: %s\n", what);
    exit(1);
}

static void set_threads(int t, cholmod_common *c) {
    openblas_set_num_threads(t);
    omp_set_num_threads(t);
    (void)c; /* CHOLMOD 3.0 has no per-call thread knob: its OpenMP loops follow omp_set_num_threads */
}

struct args {
    const char *file;
    int repeats;
    int threads[MAX_THREADS], n_threads;
    int orderings[MAX_ORDERINGS], n_orderings;
};

static void parse_threads(struct args *a, char *list) {
    for (char *tok = strtok(list, ","); tok; tok = strtok(NULL, ",")) {
        int t = atoi(tok);
        if (t < 1 || a->n_threads == MAX_THREADS) die("bad --threads list");
        a->threads[a->n_threads++] = t;
    }
}

static struct args parse(int argc, char **argv) {
    struct args a = {NULL, 5, {0}, 0, {0}, 0};
    for (int i = 1; i < argc; i++) {
        const char *x = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(x, "--repeats") && v) {
            a.repeats = atoi(v), i++;
            if (a.repeats < 1 || a.repeats > MAX_REPEATS) die("bad --repeats");
        } else if (!strcmp(x, "--threads") && v) {
            parse_threads(&a, argv[++i]);
        } else if (!strcmp(x, "--ordering") && v && a.n_orderings < MAX_ORDERINGS) {
            if (!strcmp(v, "metis")) a.orderings[a.n_orderings++] = CHOLMOD_METIS;
            else if (!strcmp(v, "amd")) a.orderings[a.n_orderings++] = CHOLMOD_AMD;
            else die("unknown --ordering (metis or amd)");
            i++;
        } else if (!a.file && x[0] != '-') {
            a.file = x;
        } else {
            die("usage: cholmod_bench FILE.mtx [--repeats R] [--threads 1,2] [--ordering metis|amd]...");
        }
    }
    if (!a.file) die("usage: cholmod_bench FILE.mtx [--repeats R] [--threads 1,2] [--ordering metis|amd]...");
    if (!a.n_threads) a.threads[0] = 1, a.threads[1] = 2, a.n_threads = 2;
    if (!a.n_orderings) a.orderings[0] = CHOLMOD_METIS, a.orderings[1] = CHOLMOD_AMD, a.n_orderings = 2;
    return a;
}

static double factorize(cholmod_sparse *A, cholmod_factor *L, cholmod_common *c) {
    double t = now();
    int ok = cholmod_factorize(A, L, c);
    t = now() - t;
    if (!ok || c->status != CHOLMOD_OK) die("cholmod_factorize failed");
    if (L->minor != L->n) die("matrix not positive definite");
    return t;
}

/* One solve L L^T X = B with two right-hand sides (a Tutte system's u and
 * v), in seconds. */
static double solve2(cholmod_factor *L, cholmod_common *c) {
    cholmod_dense *B = cholmod_ones(L->n, 2, CHOLMOD_REAL, c);
    if (!B) die("cholmod_ones failed");
    double t = now();
    cholmod_dense *X = cholmod_solve(CHOLMOD_A, L, B, c);
    t = now() - t;
    if (!X || c->status != CHOLMOD_OK) die("cholmod_solve failed");
    cholmod_free_dense(&X, c);
    cholmod_free_dense(&B, c);
    return t;
}

/* Analyse with one ordering, time R rounds over the thread counts, print. */
static void run_ordering(const struct args *a, cholmod_sparse *A, int ordering, cholmod_common *c) {
    static double times[MAX_THREADS][MAX_REPEATS], solves[MAX_THREADS];
    c->nmethods = 1;
    c->method[0].ordering = ordering;
    c->postorder = 1;
    c->supernodal = CHOLMOD_SUPERNODAL;
    set_threads(a->threads[a->n_threads - 1], c);
    double t0 = now();
    cholmod_factor *L = cholmod_analyze(A, c);
    double analyze_s = now() - t0;
    if (!L || c->status != CHOLMOD_OK) die("cholmod_analyze failed");
    double lnz = c->lnz, fl = c->fl;
    for (int k = 0; k < a->n_threads; k++) {
        set_threads(a->threads[k], c);
        factorize(A, L, c);
    }
    factorize(A, L, c);
    for (int r = 0; r < a->repeats; r++)
        for (int k = 0; k < a->n_threads; k++) {
            set_threads(a->threads[k], c);
            times[k][r] = factorize(A, L, c);
        }
    for (int k = 0; k < a->n_threads; k++) {
        set_threads(a->threads[k], c);
        solves[k] = solve2(L, c);
    }
    for (int k = 0; k < a->n_threads; k++) {
        double best = times[k][0], sum = 0.0;
        for (int r = 0; r < a->repeats; r++) {
            if (times[k][r] < best) best = times[k][r];
            sum += times[k][r];
        }
        printf("{\"solver\":\"cholmod\",\"matrix\":\"%s\",\"n\":%zu,\"nnz_a\":%zu,"
               "\"ordering\":\"%s\",\"threads\":%d,\"supernodal\":%s,\"nnz_l\":%.0f,"
               "\"l_stored\":%zu,\"flops\":%.6e,\"analyze_s\":%.6f,\"factor_best_s\":%.6f,"
               "\"factor_mean_s\":%.6f,\"solve2_s\":%.6f,\"repeats\":%d,\"load1\":%.2f}\n",
               a->file, A->nrow, cholmod_nnz(A, c), ordering == CHOLMOD_METIS ? "metis" : "amd",
               a->threads[k], L->is_super ? "true" : "false", lnz,
               L->is_super ? L->xsize : L->nzmax, fl, analyze_s, best, sum / a->repeats,
               solves[k], a->repeats, load1());
        fflush(stdout);
    }
    cholmod_free_factor(&L, c);
}

int main(int argc, char **argv) {
    struct args a = parse(argc, argv);
    cholmod_common c;
    cholmod_start(&c);
    FILE *f = fopen(a.file, "r");
    if (!f) die("cannot open the matrix file");
    cholmod_sparse *A = cholmod_read_sparse(f, &c);
    fclose(f);
    if (!A || A->stype == 0) die("not a symmetric Matrix Market file");
    for (int o = 0; o < a.n_orderings; o++) run_ordering(&a, A, a.orderings[o], &c);
    cholmod_free_sparse(&A, &c);
    cholmod_finish(&c);
    return 0;
}
