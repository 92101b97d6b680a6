// Hussein et al.'s (2012) wall function through depo.hpp: the same particles as hussein.c,
// printed the same way, and a refused particle as a depo::Error.
#include <cstdio>
#include <iostream>

#include "depo.hpp"

int main() {
    const DepoAir air = {293.15, 101325.0, 1.204, 1.81e-5};
    const std::size_t n = 4;
    const double ustar[n] = {0.3, 0.01, 0.5, 0.2}, diameter[n] = {5e-6, 3e-6, 40e-6, 0.1e-6};
    const double density[n] = {1000.0, 1500.0, 2500.0, 1000.0}, layer[n] = {1.5e-3, 0.045, 2e-3, 4e-3};
    const double gravity = 9.80665, dt = 1e-3;
    for (std::int32_t s = DEPO_SURFACE_FLOOR; s <= DEPO_SURFACE_WALL; s++) {
        double v[n], p[n];
        depo::deposition_velocity(DEPO_CORRELATION_HUSSEIN, s, air, gravity, n, ustar, diameter, density, v);
        depo::wall_function_probability(DEPO_CORRELATION_HUSSEIN, s, air, gravity, dt, n, ustar, layer, diameter,
                                        density, p);
        for (std::size_t i = 0; i < n; i++)
            std::printf("hussein %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", static_cast<int>(s), ustar[i],
                        diameter[i], density[i], layer[i], dt, v[i], p[i]);
    }
    double u = 10.0, d = 1e-3, rho = 1000.0, out = -1.0;
    try {
        depo::deposition_velocity(DEPO_CORRELATION_HUSSEIN, DEPO_SURFACE_WALL, air, gravity, 1, &u, &d, &rho, &out);
        std::printf("not refused\n");
    } catch (const depo::Error &e) {
        std::printf("refused %d %g %s\n", static_cast<int>(e.status()), out, e.what());
    }
    return 0;
}
