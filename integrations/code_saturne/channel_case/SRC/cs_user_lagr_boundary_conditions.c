/* Channel: both walls are Code_Saturne's deposition walls, CS_LAGR_DEPO1: a particle that
   reaches one deposits and leaves the particle set. With the deposition model on, the
   model carries the particles through the wall cells and decides when they reach it. */

#include "cs_defs.h"
#include "cs_boundary_zone.h"
#include "cs_lagr.h"
#include "cs_prototypes.h"

BEGIN_C_DECLS

void
cs_user_lagr_boundary_conditions(const int  bc_type[])
{
  CS_UNUSED(bc_type);
  cs_lagr_zone_data_t *bcs = cs_lagr_get_boundary_conditions();
  bcs->zone_type[cs_boundary_zone_by_name("floor")->id] = CS_LAGR_DEPO1;
  bcs->zone_type[cs_boundary_zone_by_name("ceiling")->id] = CS_LAGR_DEPO1;
}

END_C_DECLS
