/* The duct case's stages, particles and time line, and the census of where they went. */

#ifndef DUCT_H
#define DUCT_H

/* What a run is, from the file `walls` in DATA: the flow stage ("flow": the flow developed
   from rest, no particles), or a particle run restarted from its checkpoint with the walls
   Code_Saturne's sink ("sink"), depo's law ("depo"), depo's deposition wall function
   ("wall-function") or Code_Saturne's deposition model ("model", Guingo & Minier 2008). */
#define DUCT_SINK 0
#define DUCT_DEPO 1
#define DUCT_WALL_FUNCTION 2
#define DUCT_MODEL 3
#define DUCT_FLOW 4

/* Time line: steps of DUCT_DT; the flow stage's DUCT_FLOW_STEPS (5 s from rest, 2.5 times
   the air's transit), then a particle run's DUCT_PARTICLE_STEPS (4 s), whose step numbers
   continue the flow stage's. A particle run injects DUCT_PER_STEP particles of each size
   per step at its steps DUCT_FIRST_STEP to DUCT_LAST_STEP (its first 2 s: 8000 a size)
   and counts them at its last step, 2 s (a transit) after the last injection. */
#define DUCT_DT 5e-3
#define DUCT_FLOW_STEPS 1000
#define DUCT_PARTICLE_STEPS 800
#define DUCT_FIRST_STEP 1
#define DUCT_LAST_STEP 400

#define DUCT_SIZES 3
#define DUCT_PER_STEP 20
#define DUCT_DENSITY 1000.0

static const double duct_diameters[DUCT_SIZES] = {10e-6, 30e-6, 100e-6};

/* DUCT_SINK, DUCT_DEPO, DUCT_WALL_FUNCTION, DUCT_MODEL or DUCT_FLOW, from the file `walls`. */
int duct_walls_mode(void);

#endif
