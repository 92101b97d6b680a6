/* Every result of libdepo's entry points on fixed inputs, printed exactly (C99's %a: the
 * double's bits in hexadecimal), so that a change of the library that alters any result by one
 * bit shows as a line of difference against tests/golden/abi.txt. Run by tests/golden.rs. */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "depo.h"

#define N 257 /* an odd count, so that the kernels' remainders run too */

static uint64_t state = 0x9E3779B97F4A7C15u;

/* A uniform number in [lo, hi) from a fixed 64-bit LCG (Knuth's MMIX constants). */
static double uniform(double lo, double hi) {
    state = state * 6364136223846793005u + 1442695040888963407u;
    return lo + (hi - lo) * (double)(state >> 11) * 0x1p-53;
}

static void check(int32_t status, const char *what) {
    if (status != DEPO_OK) {
        fprintf(stderr, "%s: status %d: %s\n", what, (int)status, depo_last_error());
        exit(1);
    }
}

static void print_tally(const char *name, const DepoTally *t) {
    printf("%s tally %" PRIu64 " %" PRIu64 " %" PRIu64 " %" PRIu64 " %a %a %a %a\n", name, t->rebound,
           t->captured, t->skipped, t->invalid, t->energy_material, t->energy_adhesion,
           t->energy_friction, t->energy_deposition);
}

/* One preset's law through every kernel: coefficients, f64 with spin, friction and
 * per-particle normals, f64 strided, f32, per-particle capture velocities. */
static void law_results(const char *id, double mu) {
    DepoWallLaw *preset = NULL, *law = NULL;
    check(depo_law_preset(id, &preset), id);
    DepoLawParams params;
    check(depo_law_params(preset, &params), "params");
    params.mu = mu;
    check(depo_law_new(&params, &law), "new");
    depo_law_free(preset);
    printf("law %s mu %a\n", id, mu);

    double vn[N], e[N], R[N], rho[N];
    uint8_t captured[N];
    for (int i = 0; i < N; i++) vn[i] = uniform(-0.5, 8.0) * params.vc + uniform(0.0, 0.1);
    check(depo_coefficients(law, N, vn, e, R, rho, captured), "coefficients");
    for (int i = 0; i < N; i++) printf("coef %d %a %a %a %a %u\n", i, vn[i], e[i], R[i], rho[i], captured[i]);

    double vx[N], vy[N], vz[N], wx[N], wy[N], wz[N], radius[N], nx[N], ny[N], nz[N];
    uint8_t outcome[N];
    for (int i = 0; i < N; i++) {
        vx[i] = uniform(-3.0, 3.0);
        vy[i] = uniform(-3.0, 3.0);
        vz[i] = uniform(-6.0, 1.0);
        wx[i] = uniform(-1e4, 1e4);
        wy[i] = uniform(-1e4, 1e4);
        wz[i] = uniform(-1e4, 1e4);
        radius[i] = uniform(1e-6, 50e-6);
        /* a normal tilted from +z, normalised */
        double a = uniform(-0.3, 0.3), b = uniform(-0.3, 0.3);
        double norm = sqrt(a * a + b * b + 1.0);
        nx[i] = a / norm;
        ny[i] = b / norm;
        nz[i] = 1.0 / norm;
    }
    vx[3] = NAN; /* a bad particle: flagged, left untouched */
    DepoImpactsF64 batch = {N, vx, vy, vz, wx, wy, wz, radius, nx, ny, nz, {0.0, 0.0, 1.0}, outcome};
    DepoTally tally = {0};
    check(depo_apply_f64(law, &batch, &tally), "apply_f64");
    for (int i = 0; i < N; i++)
        printf("f64 %d %a %a %a %a %a %a %u\n", i, vx[i], vy[i], vz[i], wx[i], wy[i], wz[i], outcome[i]);
    print_tally("f64", &tally);

    /* Interleaved (x, y, z) velocities (strides in bytes), one batch normal, no spin. */
    double v[3 * N];
    for (int i = 0; i < 3 * N; i++) v[i] = uniform(-4.0, 4.0);
    DepoImpactsF64 strided = {N, v, v + 1, v + 2, NULL, NULL, NULL, NULL, NULL, NULL, NULL, {0.0, 1.0, 0.0}, outcome};
    DepoStrides strides = {{3 * sizeof(double), 3 * sizeof(double), 3 * sizeof(double)}, {0, 0, 0}, 0, {0, 0, 0}, 1};
    DepoTally strided_tally = {0};
    check(depo_apply_strided_f64(law, &strided, &strides, &strided_tally), "apply_strided_f64");
    for (int i = 0; i < N; i++) printf("strided %d %a %a %a %u\n", i, v[3 * i], v[3 * i + 1], v[3 * i + 2], outcome[i]);
    print_tally("strided", &strided_tally);

    float fx[N], fy[N], fz[N], fcv[N];
    for (int i = 0; i < N; i++) {
        fx[i] = (float)uniform(-2.0, 2.0);
        fy[i] = (float)uniform(-2.0, 2.0);
        fz[i] = (float)uniform(-5.0, 0.5);
        fcv[i] = (float)(params.vc * uniform(0.5, 2.0));
    }
    DepoImpactsF32 fbatch = {N, fx, fy, fz, NULL, NULL, NULL, NULL, NULL, NULL, NULL, {0.0f, 0.0f, 1.0f}, outcome};
    DepoTally ftally = {0};
    check(depo_apply_sized_f32(law, &fbatch, fcv, &ftally), "apply_sized_f32");
    for (int i = 0; i < N; i++) printf("f32 %d %a %a %a %u\n", i, (double)fx[i], (double)fy[i], (double)fz[i], outcome[i]);
    print_tally("f32", &ftally);

    double diameter[N], cv[N];
    for (int i = 0; i < N; i++) diameter[i] = uniform(0.1e-6, 100e-6);
    check(depo_capture_velocities(law, 10e-6, -1.0, N, diameter, cv), "capture_velocities");
    for (int i = 0; i < N; i++) printf("vc %d %a %a\n", i, diameter[i], cv[i]);
    depo_law_free(law);
}

/* The deposition wall function for every correlation and orientation. */
static void wall_function_results(void) {
    DepoAir air = {293.15, 101325.0, 1.204, 1.81e-5};
    double ustar[N], layer[N], diameter[N], density[N], v[N], p[N];
    for (int i = 0; i < N; i++) {
        ustar[i] = uniform(0.005, 1.0);
        layer[i] = uniform(1e-4, 1e-2);
        diameter[i] = exp(uniform(log(1e-9), log(100e-6)));
        density[i] = uniform(500.0, 8000.0);
    }
    for (int c = DEPO_CORRELATION_WOOD; c <= DEPO_CORRELATION_HUSSEIN; c++) {
        for (int s = DEPO_SURFACE_FLOOR; s <= DEPO_SURFACE_WALL; s++) {
            check(depo_deposition_velocity(c, s, &air, 9.80665, N, ustar, diameter, density, v), "deposition_velocity");
            check(depo_wall_function_probability(c, s, &air, 9.80665, 1e-3, N, ustar, layer, diameter, density, p),
                  "wall_function_probability");
            for (int i = 0; i < N; i++) printf("wf %d %d %d %a %a\n", c, s, i, v[i], p[i]);
        }
    }
}

int main(void) {
    law_results("dahneke1975-quartz", 0.0);
    law_results("dunn1995-stainless", 0.3);
    law_results("li1997-sio2", 0.1);
    wall_function_results();
    return 0;
}
