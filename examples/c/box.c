/* depo from C: particles in a box, wall hits handed to depo each step, captured ones removed.
 * From the repository root, after the one release build (README), linked statically:
 *   cc -I crates/capi/include examples/c/box.c target/release/libdepo.a -lpthread -ldl -lm -o box && ./box [N]
 * or against the shared library installed by `crates/capi/install.sh $HOME/.local` (target/release
 * has libdepo.so but not the libdepo.so.0.1 a program asks for at run time; the install has both):
 *   cc examples/c/box.c $(PKG_CONFIG_PATH=$HOME/.local/lib/pkgconfig pkg-config --cflags --libs depo) -lm -o box */
#include <string.h>

#include "box_solver.h"

int main(int argc, char **argv) {
    size_t injected = argc > 1 ? (size_t)strtoull(argv[1], NULL, 10) : 20000;
    printf("depo %s\n", depo_version());

    /* Bad parameters are rejected with a message naming the field. */
    DepoWallLaw *law = NULL;
    DepoLawParams bad = {12.5, 12.5, -0.065, 0.065, 1.0, 0.5, 0.074, 0.3};
    if (depo_law_new(&bad, &law) != DEPO_ERR_INVALID || law != NULL) return 1;
    printf("rejected: %s\n", depo_last_error());

    /* Steel on SiO2 (Table 1, sim-70um: vc at 70 um) with friction 0.3; particles of 35 to 140 um. */
    DepoLawParams params = {12.5, 12.5, 0.065, 0.065, 1.0, 0.5, 0.074, 0.3};
    CHECK(depo_law_new(&params, &law));

    Box box;
    box_init(&box, law, injected, 42);
    DepoTally tally;
    memset(&tally, 0, sizeof tally);
    size_t deposited = 0;
    for (int step = 0; step < 2000; step++) deposited += box_step(&box, law, 1e-3, &tally);

    printf("injected %zu airborne %zu deposited %zu\n", injected, box.n, deposited);
    printf("tally rebound %llu captured %llu skipped %llu invalid %llu\n", (unsigned long long)tally.rebound,
           (unsigned long long)tally.captured, (unsigned long long)tally.skipped, (unsigned long long)tally.invalid);
    printf("deposited per wall (x0 x1 y0 y1 z0 z1): %llu %llu %llu %llu %llu %llu\n",
           (unsigned long long)box.deposited_on[0], (unsigned long long)box.deposited_on[1],
           (unsigned long long)box.deposited_on[2], (unsigned long long)box.deposited_on[3],
           (unsigned long long)box.deposited_on[4], (unsigned long long)box.deposited_on[5]);
    printf("energy per unit mass (J/kg): material %.4e adhesion %.4e friction %.4e deposition %.4e\n",
           tally.energy_material, tally.energy_adhesion, tally.energy_friction, tally.energy_deposition);
    box_free(&box);
    depo_law_free(law);
    uint64_t mapped = 0;
    for (int f = 0; f < 6; f++) mapped += box.deposited_on[f];
    return box.n + deposited == injected && tally.captured == deposited && mapped == deposited ? 0 : 1;
}
