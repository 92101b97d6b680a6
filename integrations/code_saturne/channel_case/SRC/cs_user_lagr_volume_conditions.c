/* Channel: at the first step of a particle stage, `particles` particles of each class
   (channel.h) are placed at random over the whole channel (Code_Saturne spreads them over
   the cells by volume and uniformly within each cell), with the fluid's velocity. */

#include "cs_defs.h"
#include "cs_lagr.h"
#include "cs_prototypes.h"
#include "cs_volume_zone.h"

#include "channel.h"

BEGIN_C_DECLS

void
cs_user_lagr_volume_conditions(void)
{
  const channel_run_t *run = channel_run();
  cs_lagr_zone_data_t *vcs = cs_lagr_get_volume_conditions();
  const cs_zone_t *all = cs_volume_zone_by_id(0);
  /* One injection set per class injected, numbered from 0 as Code_Saturne requires. */
  int set_id = 0;
  for (int c = 0; c < CHANNEL_CLASSES; c++) {
    if (!run->injected[c])
      continue;
    cs_lagr_injection_set_t *set = cs_lagr_get_injection_set(vcs, all->id, set_id++);
    set->n_inject = run->particles;
    set->injection_frequency = 0; /* the first step only */
    set->velocity_profile = -1;   /* the fluid's velocity */
    set->stat_weight = 1.0;
    set->flow_rate = 0.0;
    set->diameter = channel_diameter(c);
    set->diameter_variance = 0.0;
    set->density = CHANNEL_DENSITY;
    set->temperature_profile = 0;
  }
}

END_C_DECLS
