/* A plain C structure-of-arrays kernel of the wall law, for comparison with depo's own.
 *
 * The f64 loop of `cargo bench --bench ceiling`'s row "f64 p=1 q=1": exponents 1 and 1,
 * friction mu = 0.3, no spin, a wall with normal +z, the same constants and the same random
 * workload distribution. It computes what depo's kernel computes (capture rule, e, rolling or
 * sliding impulse, outcome byte) the straightforward way: two divisions and one square root
 * per impact, branch-free, no fast-math. A copy kernel that reads and writes the same arrays
 * is timed interleaved with it; the fraction is the median of the per-round ratios, as in
 * depo's bench.
 *
 * gcc 12 does not vectorise this loop; clang does. Build and run with
 *
 *     clang -O3 -march=native -fno-math-errno -pthread benches/c_reference/friction_kernel.c -lm
 *     ./a.out            # N = 1e7 on 2 threads, against the copy kernel
 *     ./a.out cache      # N = 4096 on one thread, in cache
 *
 * (-fno-math-errno lets sqrt vectorise; it does not change any result.)
 */
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct { double k_ratio, inv_k1, kappa_ratio, inv_kappa1, vc, capture_speed, mu; } Law;

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + t.tv_nsec * 1e-9;
}

__attribute__((noinline)) static void law_kernel(const Law *law, double *restrict vx, double *restrict vy, double *restrict vz,
                       uint8_t *restrict outcome, long n) {
  /* A local copy: read through the pointer, the constants could alias the stores to vx, vy
   * and vz, which kept clang from vectorising this loop. Not inlined, so that the in-cache
   * timing runs the same code as the threads, without constants folded into it. */
  const Law l = *law, *c = &l;
  for (long i = 0; i < n; i++) {
    double x = vx[i], y = vy[i], z = vz[i];
    double speed = -z;
    double a = fmin(fmax(c->k_ratio + speed * c->inv_k1, 1.0), 1e150);           /* Eq. 8 */
    double b = fmin(c->kappa_ratio + fabs(speed - c->vc) * c->inv_kappa1, 1e150); /* Eq. 9 */
    int captured = (speed <= c->capture_speed) | (b <= 1.0);
    double e = captured ? 0.0 : (b - 1.0) / (a * b);                              /* Eq. 2 */
    double slip = sqrt(x * x + y * y);
    double limit = (slip > 0.0 ? c->mu * fabs(speed) / slip : INFINITY) * (1.0 + e);
    double ratio = fmin(2.0 / 7.0, limit);                                        /* Eqs. 3-7 */
    double tx = captured ? 0.0 : x - ratio * x;
    double ty = captured ? 0.0 : y - ratio * y;
    double tz = captured ? 0.0 : -e * z;
    int valid = ((x - x) + (y - y) + (z - z)) == 0.0;
    int impact = speed > 0.0;
    int update = valid & impact;
    vx[i] = update ? tx : x;
    vy[i] = update ? ty : y;
    vz[i] = update ? tz : z;
    outcome[i] = !valid ? 3 : (!impact ? 2 : (captured ? 1 : 0));
  }
}

static void copy_kernel(double *restrict vx, double *restrict vy, double *restrict vz,
                        uint8_t *restrict outcome, long n) {
  for (long i = 0; i < n; i++) {
    vx[i] = -vx[i];
    vy[i] = -vy[i];
    vz[i] = -vz[i];
    outcome[i] = 1;
  }
}

typedef struct { const Law *law; double *x, *y, *z; uint8_t *o; long n; } Piece;
static void *run_law(void *p) { Piece *q = p; law_kernel(q->law, q->x, q->y, q->z, q->o, q->n); return NULL; }
static void *run_copy(void *p) { Piece *q = p; copy_kernel(q->x, q->y, q->z, q->o, q->n); return NULL; }

/* Halves the arrays between this thread and one more; returns the wall time. */
static double on_two_threads(void *(*kernel)(void *), const Law *law, double *x, double *y, double *z,
                             uint8_t *o, long n) {
  long h = n / 2;
  Piece first = {law, x, y, z, o, h}, second = {law, x + h, y + h, z + h, o + h, n - h};
  pthread_t other;
  double t0 = now();
  pthread_create(&other, NULL, kernel, &second);
  kernel(&first);
  pthread_join(other, NULL);
  return now() - t0;
}

static int by_value(const void *a, const void *b) {
  double d = *(const double *)a - *(const double *)b;
  return (d > 0) - (d < 0);
}

int main(int argc, char **argv) {
  int in_cache = argc > 1 && strcmp(argv[1], "cache") == 0;
  long n = in_cache ? 4096 : 10000000;
  /* li1997-sio2's k = 12.5, kappa = 0.065, vc = 0.074 (k1 = k2, kappa1 = kappa2), p = q = 1. */
  Law law = {1.0, 1.0 / 12.5, 1.0, 1.0 / 0.065, 0.074, 0.074, 0.3};
  double *v0[3], *v[3];
  for (int k = 0; k < 3; k++) {
    v0[k] = malloc(n * sizeof(double));
    v[k] = malloc(n * sizeof(double));
  }
  uint8_t *outcome = malloc(n);
  uint64_t s = 12345;
#define UNIFORM() (s ^= s << 13, s ^= s >> 7, s ^= s << 17, (double)(s >> 11) / 9007199254740992.0)
  for (long i = 0; i < n; i++) {
    v0[0][i] = 2 * UNIFORM() - 1;
    v0[1][i] = 2 * UNIFORM() - 1;
    v0[2][i] = -pow(10.0, 3 * UNIFORM() - 2); /* normal speeds log-uniform over 0.01..10 m/s */
  }
#define RESTORE() for (int k = 0; k < 3; k++) memcpy(v[k], v0[k], n * sizeof(double))
  if (in_cache) {
    double total = 0;
    int reps = 20000;
    for (int r = 0; r < reps; r++) {
      RESTORE();
      double t0 = now();
      law_kernel(&law, v[0], v[1], v[2], outcome, n);
      total += now() - t0;
    }
    printf("in cache, one thread: %.2f ns per impact\n", total / ((double)reps * n) * 1e9);
    return 0;
  }
  enum { ROUNDS = 9 };
  double ratio[ROUNDS], law_time[ROUNDS], copy_time[ROUNDS];
  for (int r = 0; r <= ROUNDS; r++) { /* the first round warms caches and page tables */
    RESTORE();
    double c = on_two_threads(run_copy, &law, v[0], v[1], v[2], outcome, n);
    RESTORE();
    double k = on_two_threads(run_law, &law, v[0], v[1], v[2], outcome, n);
    if (r > 0) {
      ratio[r - 1] = c / k;
      law_time[r - 1] = k;
      copy_time[r - 1] = c;
    }
  }
  qsort(ratio, ROUNDS, sizeof(double), by_value);
  qsort(law_time, ROUNDS, sizeof(double), by_value);
  qsort(copy_time, ROUNDS, sizeof(double), by_value);
  printf("N = 1e7, 2 threads: law %.0f M impacts/s, copy %.0f M impacts/s, fraction %.2f\n",
         n / law_time[ROUNDS / 2] / 1e6, n / copy_time[ROUNDS / 2] / 1e6, ratio[ROUNDS / 2]);
  return 0;
}
