/* The periodic channel: its size, the air, the driving pressure gradient, the particles and
   the stages of a run. Walls at z = 0 and z = 2H (box_mesh.py's floor and ceiling), periodic
   along x (the flow) and y (the span). */

#ifndef CHANNEL_H
#define CHANNEL_H

#include <math.h>

/* Half-height (m); LX x LY is the periodic wall patch (each wall). The mesh (mesh_args)
   has 12 cells of 4 mm across 2H: the first cell centre at 2 mm, y+ 40 at u* = 0.3 m/s. */
#define CHANNEL_H_HALF 0.024
#define CHANNEL_LX 0.06
#define CHANNEL_LY 0.04
#define CHANNEL_NZ 12 /* cells across 2H, as mesh_args */

/* Standard air, as depo's Air::standard(): 293.15 K, 1.204 kg/m^3, 1.81e-5 Pa s. */
#define CHANNEL_RHO 1.204
#define CHANNEL_MU 1.81e-5
#define CHANNEL_T 293.15

/* The friction velocity the driving gradient imposes: -dp/dx = rho u*^2 / H, so that in
   the developed flow the walls carry the whole force (Re_tau = u* H / nu = 479). */
#define CHANNEL_USTAR 0.3
#define CHANNEL_GRADIENT (CHANNEL_RHO * CHANNEL_USTAR * CHANNEL_USTAR / CHANNEL_H_HALF)

/* Particles: 1000 kg/m^3, one class per tau+ = tau u*^2 / nu with Code_Saturne's Stokes
   relaxation time tau = rho_p d^2 / (18 mu) (it has no slip correction). */
#define CHANNEL_CLASSES 6
#define CHANNEL_DENSITY 1000.0
static const double channel_tau_plus[CHANNEL_CLASSES] = {0.1, 0.3, 1.0, 3.0, 10.0, 30.0};

static inline double
channel_diameter(int c)
{
  double nu = CHANNEL_MU / CHANNEL_RHO;
  double tau = channel_tau_plus[c] * nu / (CHANNEL_USTAR * CHANNEL_USTAR);
  return sqrt(18.0 * CHANNEL_MU * tau / CHANNEL_DENSITY);
}

/* Stages, from the file `channel_run` in DATA:
     stage flow | model | no-model | wall-function
     particles N        (per class; particle stages)
     flow_steps N       (steps of the flow stage, at CHANNEL_DT_FLOW)
     particle_steps N   (steps of a particle stage)
     particle_dt S      (a particle stage's time step, s; CHANNEL_DT_PARTICLES unless given)
     classes T1,T2,...  (the tau+ of the classes injected; all of channel_tau_plus unless given)
   "flow" develops the flow from rest; "model" and "no-model" restart from it with
   particles, Code_Saturne's deposition model (Guingo & Minier 2008) on or off;
   "wall-function" restarts from it with depo's deposition wall function on both walls
   (depo_code_saturne.c, compiled in with CHANNEL_DEPO defined) and the model off. */
#define CHANNEL_FLOW 0
#define CHANNEL_MODEL 1
#define CHANNEL_NO_MODEL 2
#define CHANNEL_WALL_FUNCTION 3

#define CHANNEL_DT_FLOW 2e-3
#define CHANNEL_DT_PARTICLES 2e-4

typedef struct {
  int stage;
  long particles;
  int flow_steps;
  int particle_steps;
  double particle_dt;
  int injected[CHANNEL_CLASSES]; /* 1 for the classes injected */
} channel_run_t;

/* The run's settings, read once from `channel_run`. */
const channel_run_t *channel_run(void);

#endif
