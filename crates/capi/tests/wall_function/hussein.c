/* Hussein et al.'s (2012) wall function through the C ABI: for fixed particles in wall cells,
 * by orientation, the deposition velocity and the chance of a step, printed with 17 digits for
 * tests/examples.rs to compare with the Rust function's; each call made twice (the second
 * answered from the thread's cache) must give the same bits, and a particle larger than the
 * model's layer is refused. */
#include <stdio.h>
#include <string.h>

#include "depo.h"

#define N 4

int main(void) {
    const DepoAir air = {293.15, 101325.0, 1.204, 1.81e-5};
    /* A duct's 5 um particle, a room's 3 um one, a 40 um one, a 0.1 um one. */
    const double ustar[N] = {0.3, 0.01, 0.5, 0.2}, diameter[N] = {5e-6, 3e-6, 40e-6, 0.1e-6};
    const double density[N] = {1000.0, 1500.0, 2500.0, 1000.0}, layer[N] = {1.5e-3, 0.045, 2e-3, 4e-3};
    const double gravity = 9.80665, dt = 1e-3;
    for (int s = DEPO_SURFACE_FLOOR; s <= DEPO_SURFACE_WALL; s++) {
        double v[N], v2[N], p[N], p2[N];
        if (depo_deposition_velocity(DEPO_CORRELATION_HUSSEIN, s, &air, gravity, N, ustar, diameter, density, v) ||
            depo_deposition_velocity(DEPO_CORRELATION_HUSSEIN, s, &air, gravity, N, ustar, diameter, density, v2) ||
            depo_wall_function_probability(DEPO_CORRELATION_HUSSEIN, s, &air, gravity, dt, N, ustar, layer, diameter,
                                           density, p) ||
            depo_wall_function_probability(DEPO_CORRELATION_HUSSEIN, s, &air, gravity, dt, N, ustar, layer, diameter,
                                           density, p2)) {
            fprintf(stderr, "failed: %s\n", depo_last_error());
            return 1;
        }
        if (memcmp(v, v2, sizeof v) || memcmp(p, p2, sizeof p)) {
            fprintf(stderr, "a repeated call changed its answer\n");
            return 1;
        }
        for (int i = 0; i < N; i++)
            printf("hussein %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", s, ustar[i], diameter[i], density[i],
                   layer[i], dt, v[i], p[i]);
    }
    /* 1 mm at 10 m/s: a radius of 332 wall units. Nothing written. */
    double u = 10.0, d = 1e-3, rho = 1000.0, out = -1.0;
    int32_t status = depo_deposition_velocity(DEPO_CORRELATION_HUSSEIN, DEPO_SURFACE_WALL, &air, gravity, 1, &u, &d,
                                              &rho, &out);
    printf("refused %d %g %s\n", (int)status, out, depo_last_error());
    return 0;
}
