/* depo inside Code_Saturne: the Brach & Dunn wall law at every particle-wall contact of a
   boundary zone of type CS_LAGR_BC_USER, and depo's deposition wall function on zones of
   meshes that do not resolve the near-wall layer. See README.md beside this file. */

#ifndef DEPO_CODE_SATURNE_H
#define DEPO_CODE_SATURNE_H

#include "cs_defs.h"
#include "cs_lagr.h"

BEGIN_C_DECLS

/* Reads the zone laws from the file `depo_zones` in the run directory, makes one depo law per
   listed boundary zone, and sets those zones' Lagrangian type to CS_LAGR_BC_USER. Call it from
   cs_user_lagr_boundary_conditions(), after setting the other zones' types. Stops the run with
   a message naming the line when the file is missing or wrong. */
void
depo_cs_setup(cs_lagr_zone_data_t *lagr_bcs);

/* Impacts handled so far on this rank, per outcome (DEPO_REBOUND, DEPO_CAPTURED,
   DEPO_SKIPPED, DEPO_INVALID). */
void
depo_cs_counts(unsigned long long counts[4]);

/* Time this rank spent in depo_apply_f64 so far, s (the cost of the law inside the hook). */
double
depo_cs_apply_time(void);

/* depo's deposition wall function on the zones `depo_zones` gives one (`<zone> wall-function
   <correlation>`): each particle in a cell with a face on such a zone deposits with the chance
   depo_wall_function_probability() gives for the step, and is removed from the particle set
   as CS_LAGR_DEPO1 removes deposits. Call it once per Lagrangian step, from
   cs_user_lagr_extra_operations(), after depo_cs_setup() has run. Needs the boundary field
   `ustar` (the wall-function friction velocity of each face). */
void
depo_cs_wall_function(void);

/* Particles the wall function deposited so far on this rank. */
unsigned long long
depo_cs_wall_function_deposits(void);

END_C_DECLS

#endif
