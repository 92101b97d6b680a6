/* A minimal Lagrangian solver loop for the examples: particles of 35 to 140 um under gravity
 * in a unit box. Each particle's capture velocity follows from its diameter (depo, once at
 * injection). Each step moves them, gathers the ones that crossed a wall into one batch of hits
 * (with the wall's normal and the particle's capture velocity per hit), lets depo decide
 * rebound or capture, writes the rebounds back and removes the captured particles. Shared by
 * the C and MPI examples. */
#ifndef BOX_SOLVER_H
#define BOX_SOLVER_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "depo.h"

#define CHECK(call)                                                                       \
    do {                                                                                  \
        int32_t status_ = (call);                                                         \
        if (status_ != DEPO_OK) {                                                         \
            fprintf(stderr, "%s failed (%d): %s\n", #call, (int)status_, depo_last_error()); \
            exit(1);                                                                      \
        }                                                                                 \
    } while (0)

typedef struct {
    size_t n;            /* airborne particles */
    double *x[3], *v[3]; /* positions (m) and velocities (m/s), structure of arrays */
    double *vc;          /* capture velocity of each particle (m/s), from its diameter */
    /* the batch of wall hits of one step */
    size_t *hit_index;
    double *hv[3], *hn[3], *hvc;
    int64_t *hface; /* which wall each hit is on: 2 axis + (1 on the far wall) */
    uint8_t *outcome;
    uint64_t deposited_on[6]; /* the deposition map: particles captured per wall */
} Box;

/* A small portable generator, so every platform draws the same particles. */
static double box_uniform(uint64_t *state) {
    *state = *state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*state >> 11) / 9007199254740992.0;
}

static void box_init(Box *box, const DepoWallLaw *law, size_t n, uint64_t seed) {
    box->n = n;
    box->vc = malloc(n * sizeof(double));
    box->hvc = malloc(n * sizeof(double));
    box->hface = malloc(n * sizeof(int64_t));
    for (int f = 0; f < 6; f++) box->deposited_on[f] = 0;
    double *diameter = malloc(n * sizeof(double));
    for (int a = 0; a < 3; a++) {
        box->x[a] = malloc(n * sizeof(double));
        box->v[a] = malloc(n * sizeof(double));
        box->hv[a] = malloc(n * sizeof(double));
        box->hn[a] = malloc(n * sizeof(double));
    }
    box->hit_index = malloc(n * sizeof(size_t));
    box->outcome = malloc(n);
    for (size_t i = 0; i < n; i++) {
        for (int a = 0; a < 3; a++) {
            box->x[a][i] = 0.05 + 0.9 * box_uniform(&seed);
            /* speeds from a few cm/s to a few m/s: both sides of the capture velocity */
            box->v[a][i] = (box_uniform(&seed) - 0.5) * 4.0 * box_uniform(&seed);
        }
        diameter[i] = 35e-6 + 105e-6 * box_uniform(&seed);
    }
    /* the law's vc holds at 70 um; vc ~ d^-1.51 across sizes (paper Fig. 8) */
    CHECK(depo_capture_velocities(law, 70e-6, 1.51, n, diameter, box->vc));
    free(diameter);
}

static void box_free(Box *box) {
    for (int a = 0; a < 3; a++) {
        free(box->x[a]);
        free(box->v[a]);
        free(box->hv[a]);
        free(box->hn[a]);
    }
    free(box->hit_index);
    free(box->outcome);
    free(box->vc);
    free(box->hvc);
    free(box->hface);
}

/* One time step of length dt (s); returns the number of particles deposited in it. */
static size_t box_step(Box *box, const DepoWallLaw *law, double dt, DepoTally *tally) {
    const double gravity = -9.81;
    size_t hits = 0;
    for (size_t i = 0; i < box->n; i++) {
        box->v[2][i] += gravity * dt;
        int wall_axis = -1;
        double normal_sign = 0.0;
        for (int a = 0; a < 3; a++) {
            double x = box->x[a][i] + box->v[a][i] * dt;
            if (x < 0.0 || x > 1.0) {
                /* reflect the position into the box; the first wall crossed takes the impact */
                x = x < 0.0 ? -x : 2.0 - x;
                if (wall_axis < 0) {
                    wall_axis = a;
                    normal_sign = box->x[a][i] + box->v[a][i] * dt < 0.0 ? 1.0 : -1.0;
                }
            }
            box->x[a][i] = x;
        }
        if (wall_axis >= 0) {
            box->hit_index[hits] = i;
            for (int a = 0; a < 3; a++) {
                box->hv[a][hits] = box->v[a][i];
                box->hn[a][hits] = a == wall_axis ? normal_sign : 0.0;
            }
            box->hvc[hits] = box->vc[i];
            box->hface[hits] = 2 * wall_axis + (normal_sign < 0.0 ? 1 : 0);
            hits++;
        }
    }
    DepoImpactsF64 batch = {
        .n = hits,
        .vx = box->hv[0], .vy = box->hv[1], .vz = box->hv[2],
        .wx = NULL, .wy = NULL, .wz = NULL, .radius = NULL,
        .nx = box->hn[0], .ny = box->hn[1], .nz = box->hn[2],
        .normal = {0.0, 0.0, 1.0},
        .outcome = box->outcome,
    };
    CHECK(depo_apply_sized_f64(law, &batch, box->hvc, tally));
    CHECK(depo_accumulate_deposits(hits, box->outcome, box->hface, NULL, 6, box->deposited_on, NULL));

    /* write back rebounds; mark captured particles, then remove them keeping the order */
    size_t deposited = 0;
    for (size_t k = 0; k < hits; k++) {
        size_t i = box->hit_index[k];
        if (box->outcome[k] == DEPO_CAPTURED) {
            box->x[0][i] = -1.0; /* marker */
            deposited++;
        } else {
            for (int a = 0; a < 3; a++) box->v[a][i] = box->hv[a][k];
        }
    }
    size_t kept = 0;
    for (size_t i = 0; i < box->n; i++) {
        if (box->x[0][i] < 0.0) continue;
        for (int a = 0; a < 3; a++) {
            box->x[a][kept] = box->x[a][i];
            box->v[a][kept] = box->v[a][i];
        }
        box->vc[kept] = box->vc[i];
        kept++;
    }
    box->n = kept;
    return deposited;
}

#endif /* BOX_SOLVER_H */
