/* depo inside an MPI solver: every rank applies the law to its own particles; the tallies
 * are reduced to rank 0. depo needs no distribution layer of its own.
 * From the repository root, after the one release build (README), linked statically:
 *   mpicc -I crates/capi/include -I examples/c examples/mpi/box_mpi.c target/release/libdepo.a -lpthread -ldl -lm -o box_mpi
 * or after `crates/capi/install.sh $HOME/.local`, with PKG_CONFIG_PATH=$HOME/.local/lib/pkgconfig:
 *   mpicc -I examples/c examples/mpi/box_mpi.c $(pkg-config --cflags --libs depo) -lm -o box_mpi
 * then: mpirun -np 2 ./box_mpi [N per rank] */
#include <mpi.h>
#include <string.h>

#include "box_solver.h"

int main(int argc, char **argv) {
    MPI_Init(&argc, &argv);
    int rank, size;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    size_t injected = argc > 1 ? (size_t)strtoull(argv[1], NULL, 10) : 20000;

    CHECK(depo_set_num_threads(1)); /* one rank per core: no threads of depo's own */
    DepoWallLaw *law = NULL;
    CHECK(depo_law_preset("sim-70um", &law));

    Box box;
    box_init(&box, law, injected, 1000 + (uint64_t)rank); /* each rank its own particles */
    DepoTally tally;
    memset(&tally, 0, sizeof tally);
    unsigned long long local[6] = {0}, total[6] = {0};
    for (int step = 0; step < 2000; step++) local[5] += box_step(&box, law, 1e-3, &tally);
    local[0] = tally.rebound;
    local[1] = tally.captured;
    local[2] = tally.skipped;
    local[3] = tally.invalid;
    local[4] = box.n;
    MPI_Reduce(local, total, 6, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
    double energy[4] = {tally.energy_material, tally.energy_adhesion, tally.energy_friction, tally.energy_deposition};
    double energy_total[4];
    MPI_Reduce(energy, energy_total, 4, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);

    int ok = 1;
    if (rank == 0) {
        unsigned long long all = (unsigned long long)injected * (unsigned long long)size;
        printf("ranks %d injected %llu airborne %llu deposited %llu\n", size, all, total[4], total[5]);
        printf("tally rebound %llu captured %llu skipped %llu invalid %llu\n", total[0], total[1], total[2], total[3]);
        printf("energy per unit mass (J/kg): material %.4e adhesion %.4e\n", energy_total[0], energy_total[1]);
        ok = total[4] + total[5] == all && total[1] == total[5];
    }
    box_free(&box);
    depo_law_free(law);
    MPI_Finalize();
    return ok ? 0 : 1;
}
