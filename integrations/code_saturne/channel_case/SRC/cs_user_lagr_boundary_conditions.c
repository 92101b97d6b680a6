/* Channel: both walls are Code_Saturne's deposition walls, CS_LAGR_DEPO1: a particle that
   reaches one deposits and leaves the particle set. With the deposition model on, the
   model carries the particles through the wall cells and decides when they reach it.
   In the wall-function stage, depo_cs_setup() turns the zones `depo_zones` lists (both
   walls, `wall-function wood`) into elastic rebound walls: depo's wall function deposits
   the particles of the wall cells instead (channel_census.c calls it every step). */

#include "cs_defs.h"
#include "bft_error.h"
#include "cs_boundary_zone.h"
#include "cs_lagr.h"
#include "cs_prototypes.h"

#include "channel.h"
#ifdef CHANNEL_DEPO
#include "depo_code_saturne.h"
#endif

BEGIN_C_DECLS

void
cs_user_lagr_boundary_conditions(const int  bc_type[])
{
  CS_UNUSED(bc_type);
  cs_lagr_zone_data_t *bcs = cs_lagr_get_boundary_conditions();
  bcs->zone_type[cs_boundary_zone_by_name("floor")->id] = CS_LAGR_DEPO1;
  bcs->zone_type[cs_boundary_zone_by_name("ceiling")->id] = CS_LAGR_DEPO1;
  if (channel_run()->stage == CHANNEL_WALL_FUNCTION) {
#ifdef CHANNEL_DEPO
    depo_cs_setup(bcs);
#else
    bft_error(__FILE__, __LINE__, 0, "channel: the wall-function stage needs libdepo "
              "(run_channel.sh compiles it in with DEPO_PREFIX)\n");
#endif
  }
}

END_C_DECLS
