/* The duct case's particles and the census of where they went. */

#ifndef DUCT_H
#define DUCT_H

#define DUCT_SINK 0
#define DUCT_DEPO 1
#define DUCT_WALL_FUNCTION 2

#define DUCT_SIZES 3
#define DUCT_PER_STEP 20
#define DUCT_FIRST_STEP 200
#define DUCT_LAST_STEP 599
#define DUCT_DENSITY 1000.0

static const double duct_diameters[DUCT_SIZES] = {10e-6, 30e-6, 100e-6};

/* DUCT_SINK, DUCT_DEPO or DUCT_WALL_FUNCTION, from the file `walls`. */
int duct_walls_mode(void);

#endif
